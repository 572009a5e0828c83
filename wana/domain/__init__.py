"""The domain library: what several services need as code, not as messages.

Why a ``wana.domain`` sub-package and not ``wana/`` itself (as DESIGN.md's table puts it): ``wana/``
also holds the command line and the composition root (``wana.cli``, ``wana.compose``), which must
import services, so "the domain library imports no service" can only be checked on a package that
holds nothing else. ``wana.assets`` (the object catalog, its query API ``catalog.asset_for`` /
``make_object``, the scene database), ``wana.bus`` and ``wana.arrays`` are domain-level too and
sit under the same import-linter contract; they keep their names because they are large and widely
imported.

Modules (fairmotion's core/data/ops layering; none imports a service):
    skeleton        the canonical skeleton: joint names, parents, rest offsets (Mixamo names)
    quat            quaternions (x, y, z, w), Euler conversions, slerp
    posing          the neutral standing pose and limb-aiming helpers that clip files are relative to
    bvh             BVH reading and writing on the canonical skeleton
    actions         the action catalogue: clips read from assets/actions (names, synonyms, tags,
                    contacts, the object each needs, the contact point each prefers) and their sampling
    object_geometry catalog collision boxes as oriented world boxes, floor footprints of a scene
    routes          occupancy grid and A* walking routes
    units           metres, Y up, and the one frame rate ``FPS``
    paths           where packaged assets and models are, in a checkout or an installed wheel
"""
