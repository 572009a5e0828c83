"""The procedural object catalog: category + attribute knobs + seed -> AssetObject.

Object frame: base centre at the origin, Y up, the front faces +Z, metres. Every object carries its
mesh (per-face colours), dimensions, collision boxes from voxelising its parts, contact points per
interaction, the spot where a character stands to interact, and horizontal support surfaces.

    >>> chair = make_object("office_chair", {"colour": "red"})
    >>> chair.contact_points["sit"].joint
    'Hips'

Objects are cached; treat them as read-only (arrays are marked non-writeable; copy the mesh before
editing it).
"""

from __future__ import annotations

import hashlib
import itertools
from dataclasses import dataclass, field
from functools import lru_cache
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import ArrayLike

from proto.scene import PlacedObject
from wana.assets import vocabulary
from wana.assets.generators import REGISTRY
from wana.assets.generators.registry import run
from wana.assets.geometry import build_mesh, voxel_boxes
from wana.assets.params import (
    COLOURS,
    MATERIALS,
    SIZE_FACTORS,
    STYLES,
    TONES,
    Builder,
    Params,
    _rgba,
    mix,
)

if TYPE_CHECKING:  # trimesh comes with the first object built (wana.assets.geometry.build_mesh)
    import trimesh
    from trimesh.visual import ColorVisuals

FRONT = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class ContactPoint:
    """Where a joint goes for an interaction.

    Attributes:
        joint: canonical (Mixamo) joint name, e.g. "Hips", "RightHandMiddle1".
        position: (3,) object frame, metres.
        extra: other joints of the same interaction (e.g. the left hand when typing) -> (3,) positions.
    """

    joint: str
    position: np.ndarray
    extra: dict[str, np.ndarray] = field(default_factory=dict)


@dataclass(frozen=True)
class SupportSurface:
    """A horizontal rectangle things can rest on: y = height, x/z within [min_xz, max_xz] (object frame)."""

    height: float
    min_xz: np.ndarray  # (2,) metres
    max_xz: np.ndarray  # (2,) metres


@dataclass(frozen=True)
class AssetObject:
    """One catalog object (see module docstring for the frame).

    Attributes:
        category: catalog category.
        attributes: the effective knob values (normalised, only knobs that apply).
        seed: variant seed.
        mesh: triangle mesh with per-face colours.
        dims: (3,) width (x), height (y), depth (z) in metres.
        collision_boxes: (N, 2, 3) min/max corners of small boxes from voxelisation.
        contact_points: interaction name -> ContactPoint.
        stand_point: (3,) where a character stands to interact (y = 0, on the floor under the base).
        support_surfaces: horizontal surfaces other objects can rest on.
        front: (3,) unit front direction (+Z).
    """

    category: str
    attributes: dict[str, str]
    seed: int
    mesh: trimesh.Trimesh
    dims: np.ndarray
    collision_boxes: np.ndarray
    contact_points: dict[str, ContactPoint]
    stand_point: np.ndarray
    support_surfaces: list[SupportSurface]
    front: np.ndarray

    @property
    def mount(self) -> str:
        """ "floor", "surface" or "wall" (from the vocabulary)."""
        info = vocabulary.CATEGORIES.get(self.category)
        return info.mount if info else "floor"


def categories() -> list[str]:
    """All catalog categories (each has a generator), in vocabulary order."""
    return [c for c in vocabulary.CATEGORIES if c in REGISTRY]


def variant_space(category: str) -> dict[str, tuple[str, ...]]:
    """Knob -> values that change this category's mesh."""
    info = _info(category)
    return {k: vocabulary.KNOB_VALUES[k] for k in info.knobs}


def count_variants(category: str | None = None) -> int:
    """Number of distinct knob combinations (every applicable knob set to one of its values)."""
    cats = [category] if category else categories()
    return int(sum(np.prod([len(v) for v in variant_space(c).values()]) for c in cats))


def iter_variants(category: str) -> itertools.product:
    """All attribute dicts of a category's variant space, as tuples of (knob, value) pairs."""
    space = variant_space(category)
    return itertools.product(*[[(k, v) for v in vals] for k, vals in space.items()])


def _info(category: str) -> vocabulary.CategoryInfo:
    if category not in vocabulary.CATEGORIES or category not in REGISTRY:
        raise KeyError(f"unknown catalog category {category!r}; see wana.assets.catalog.categories()")
    return vocabulary.CATEGORIES[category]


def normalize_attributes(category: str, attributes: dict[str, str] | None) -> dict[str, str]:
    """Keep knobs that apply to the category, with canonical values; drop words it cannot use.

    Values may be any attribute word ("tidy", "gray", "oak"); a value of the wrong knob is moved to
    its own knob when that knob applies ({"colour": "wooden"} -> {"material": "wooden"}).
    """
    info = _info(category)
    out: dict[str, str] = {}
    for knob, value in (attributes or {}).items():
        norm = vocabulary.normalize_attribute(str(value))
        if norm is None:
            continue
        real_knob, canonical = norm
        if real_knob in info.knobs and (knob == real_knob or real_knob not in out):
            out[real_knob] = canonical
    return dict(sorted(out.items()))


def make_object(category: str, attributes: dict[str, str] | None = None, seed: int = 0) -> AssetObject:
    """Build (or fetch from the cache) one catalog object.

    Args:
        category: a name from ``categories()``.
        attributes: knob -> value, e.g. {"colour": "red", "style": "modern"}; words that do not
            apply to the category are ignored.
        seed: variant seed (0 = the canonical variant; others jitter proportions and shades).

    Raises:
        KeyError: for an unknown category.
    """
    attrs = normalize_attributes(category, attributes)
    return _make_cached(category, tuple(attrs.items()), int(seed))


@lru_cache(maxsize=4096)
def _make_cached(category: str, attrs: tuple[tuple[str, str], ...], seed: int) -> AssetObject:
    spec = REGISTRY[category]
    a = dict(attrs)
    params = _params(category, spec, a, seed)
    b = Builder()
    run(spec, b, params)
    return _finish(category, a, seed, b, params)


def _params(category: str, spec, a: dict[str, str], seed: int) -> Params:  # noqa: ANN001
    style = STYLES[a.get("style", "")]
    rng = np.random.default_rng(seed)
    jitter = np.ones(3) if seed == 0 else rng.uniform(0.94, 1.06, 3)
    size = SIZE_FACTORS.get(a.get("size", "medium"), 1.0)
    w, h, d = np.asarray(spec.dims) * size * np.asarray(style.dims) * jitter
    material = a.get("material", "")
    colour = a.get("colour", "")
    body = TONES[spec.body]
    frame = TONES[spec.frame]
    if colour and material:
        body = mix(COLOURS[colour], MATERIALS[material], 0.3)
    elif colour:
        body = COLOURS[colour]
    elif material:
        body = mix(MATERIALS[material], body, 0.15)
    if material:
        frame = mix(MATERIALS[material], (0, 0, 0), 0.15)
    k = style.tint * (1.0 if seed == 0 else float(rng.uniform(0.9, 1.1)))
    return Params(
        category=category,
        w=float(w),
        h=float(h),
        d=float(d),
        style=style,
        body=_rgba(body, k),
        frame=_rgba(frame, style.tint),
        accent=_rgba(TONES[spec.accent]),
        state=a.get("state", ""),
        material=material,
        seed=seed,
        rng=np.random.default_rng(seed + 1),
    )


def _frozen(x: ArrayLike) -> np.ndarray:
    x = np.asarray(x, dtype=np.float64)
    x.setflags(write=False)
    return x


def _finish(category: str, attrs: dict[str, str], seed: int, b: Builder, p: Params) -> AssetObject:
    mesh = build_mesh(b.parts)
    lo, hi = mesh.bounds
    shift = np.array([-(lo[0] + hi[0]) / 2.0, -lo[1], -(lo[2] + hi[2]) / 2.0])
    mesh.apply_translation(shift)
    for part in b.parts:
        part.translation = part.translation + shift
    bounds = mesh.bounds.copy()
    dims = bounds[1] - bounds[0]
    boxes = voxel_boxes(b.parts, bounds)
    contacts = {
        name: ContactPoint(
            c.joint,
            _frozen(np.asarray(c.position) + shift),
            {j: _frozen(np.asarray(q) + shift) for j, q in c.extra.items()},
        )
        for name, c in b.contacts.items()
    }
    mount = vocabulary.CATEGORIES[category].mount
    top = float(dims[1])
    if "touch" not in contacts:
        y = min(top * 0.8, 1.2) if mount != "surface" else top * 0.6
        contacts["touch"] = ContactPoint("RightHandMiddle1", _frozen([0.0, y, dims[2] / 2.0]))
    if mount == "surface" and "pick_up" not in contacts:
        contacts["pick_up"] = ContactPoint("RightHandMiddle1", _frozen([0.0, top * 0.6, 0.0]))
    if b.stand is not None:
        stand = np.asarray(b.stand, float) + shift
        stand[1] = 0.0
    else:
        stand = np.array([0.0, 0.0, dims[2] / 2.0 + 0.35])
    surfaces = [
        SupportSurface(
            y + shift[1], _frozen([x0 + shift[0], z0 + shift[2]]), _frozen([x1 + shift[0], z1 + shift[2]])
        )
        for y, x0, z0, x1, z1 in b.surfaces
    ]
    for arr in (mesh.vertices, mesh.faces):
        arr.flags.writeable = False
    return AssetObject(
        category=category,
        attributes=dict(attrs),
        seed=seed,
        mesh=mesh,
        dims=_frozen(dims),
        collision_boxes=_frozen(boxes),
        contact_points=contacts,
        stand_point=_frozen(stand),
        support_surfaces=surfaces,
        front=_frozen(FRONT),
    )


def mesh_digest(obj: AssetObject) -> str:
    """Content hash of an object's geometry and colours (distinct variants have distinct digests)."""
    h = hashlib.sha1()
    h.update(np.round(np.asarray(obj.mesh.vertices), 5).tobytes())
    visual = cast("ColorVisuals", obj.mesh.visual)  # catalogue meshes carry per-face colours
    h.update(np.asarray(visual.face_colors).tobytes())
    return h.hexdigest()


# ---------------------------------------------------------------------------------------------
# Placement in the world


def yaw_matrix(yaw: float) -> np.ndarray:
    """(3, 3) rotation about +Y by yaw radians (0 keeps the front on +Z)."""
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def object_to_world(placed: PlacedObject) -> np.ndarray:
    """(4, 4) transform object frame -> world: translate(position) @ rotY(yaw) @ scale."""
    m = np.eye(4)
    m[:3, :3] = yaw_matrix(placed.yaw) @ np.diag(placed.scale)
    m[:3, 3] = placed.position
    return m


def asset_for(placed: PlacedObject) -> AssetObject:
    """The catalog object a placement refers to (imported objects first, see importers.register)."""
    from wana.assets.importers.registry import imported_object

    obj = imported_object(placed.category)
    return obj if obj is not None else make_object(placed.category, placed.attributes, placed.seed)


def transform_boxes(boxes: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """AABBs (N, 2, 3) of boxes (N, 2, 3) after a (4, 4) transform."""
    corners = np.stack(
        [boxes[:, [i, j, k], [0, 1, 2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)], axis=1
    )
    world = corners @ matrix[:3, :3].T + matrix[:3, 3]
    return np.stack([world.min(axis=1), world.max(axis=1)], axis=1)


def world_collision_boxes(placed: PlacedObject) -> np.ndarray:
    """(N, 2, 3) world-frame AABBs of the placed object's collision boxes (after yaw and scale)."""
    return transform_boxes(asset_for(placed).collision_boxes, object_to_world(placed))


def world_bounds(placed: PlacedObject) -> np.ndarray:
    """(2, 3) world AABB of the placed object's mesh box (dims), after yaw and scale."""
    obj = asset_for(placed)
    half = obj.dims / 2.0
    box = np.array([[[-half[0], 0.0, -half[2]], [half[0], obj.dims[1], half[2]]]])
    return transform_boxes(box, object_to_world(placed))[0]


def to_world(placed: PlacedObject, points: np.ndarray) -> np.ndarray:
    """Object-frame points (..., 3) -> world frame."""
    m = object_to_world(placed)
    return np.asarray(points, float) @ m[:3, :3].T + m[:3, 3]


def world_support_surfaces(placed: PlacedObject) -> list[tuple[float, np.ndarray]]:
    """Each support surface as (world height, (4, 2) world x/z corners of its rectangle)."""
    out = []
    for s in asset_for(placed).support_surfaces:
        (x0, z0), (x1, z1) = s.min_xz, s.max_xz
        pts = np.array([[x0, s.height, z0], [x1, s.height, z0], [x1, s.height, z1], [x0, s.height, z1]])
        w = to_world(placed, pts)
        out.append((float(w[0, 1]), w[:, [0, 2]]))
    return out
