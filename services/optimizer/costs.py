"""The paper's costs (Zhang et al. 2021, §4.3), batched over K candidate layouts.

Collision cost, eq. 1: for each object the body hits during the motion, the share of that object's
collision boxes that are hit, averaged over the hit objects (0 when nothing is hit):

    C_D = 1/|H| · Σ_{o ∈ H} |hit boxes of o| / |boxes of o|

Contact cost, eq. 2: the mean over contact pairs of the distance between the object's contact point
and the mean position of its joint over the action's frames:

    C_T = 1/|P| · Σ_{(c, j) ∈ P} ‖ p_c − mean_t x_j(t) ‖

Total C = λ_D·C_D + λ_T·C_T. The body is the sphere sampling of the bone capsules
(services.optimizer.body); a sphere hits a box when its centre is closer to the oriented box than
its radius, less a tolerance for the objects the action touches on purpose (hips on a seat).
A broad phase (body bounding box per frame against box bounding boxes) keeps the exact test to the
few frame/box pairs that can touch.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from proto.scene import Scene
from services.optimizer.body import BodySpheres
from wana.domain.object_geometry import object_shape
from wana.domain.skeleton import JOINT_INDEX


@dataclass(frozen=True)
class SceneGeometry:
    """Object-frame boxes and contact points of a scene's objects, flattened for batching.

    Attributes:
        ids: (O,) object ids in scene order.
        box_centre: (B, 3) box centres, object frame, metres.
        box_half: (B, 3) box half extents, object frame, metres.
        box_owner: (B,) object index of each box.
        boxes_per_object: (O,) number of boxes per object.
        contact_owner: (C,) object index of each contact point.
        contact_local: (C, 3) contact point positions, object frame.
        contact_names: (C,) contact point names.
        contact_joints: (C,) canonical joint names.
    """

    ids: tuple[str, ...]
    box_centre: np.ndarray
    box_half: np.ndarray
    box_owner: np.ndarray
    boxes_per_object: np.ndarray
    contact_owner: np.ndarray
    contact_local: np.ndarray
    contact_names: tuple[str, ...]
    contact_joints: tuple[str, ...]

    @staticmethod
    def from_scene(scene: Scene) -> SceneGeometry:
        """Read every object's geometry from the asset catalog (cached per variant)."""
        centre, half, owner, counts = [], [], [], []
        c_owner, c_local, c_names, c_joints = [], [], [], []
        for i, obj in enumerate(scene.objects):
            shape = object_shape(obj)
            centre.append(shape.boxes.mean(axis=1))
            half.append((shape.boxes[:, 1] - shape.boxes[:, 0]) / 2)
            owner.append(np.full(len(shape.boxes), i))
            counts.append(len(shape.boxes))
            c_owner += [i] * len(shape.contact_names)
            c_local.append(shape.contact_positions)
            c_names += list(shape.contact_names)
            c_joints += list(shape.contact_joints)
        return SceneGeometry(
            ids=tuple(o.id for o in scene.objects),
            box_centre=np.concatenate(centre) if centre else np.zeros((0, 3)),
            box_half=np.concatenate(half) if half else np.zeros((0, 3)),
            box_owner=np.concatenate(owner).astype(np.int64) if owner else np.zeros(0, np.int64),
            boxes_per_object=np.array(counts, dtype=np.int64),
            contact_owner=np.array(c_owner, dtype=np.int64),
            contact_local=np.concatenate(c_local).reshape(-1, 3) if c_local else np.zeros((0, 3)),
            contact_names=tuple(c_names),
            contact_joints=tuple(c_joints),
        )

    @staticmethod
    def from_arrays(
        objects: list[tuple[str, np.ndarray, dict[str, tuple[np.ndarray, str]]]],
    ) -> SceneGeometry:
        """Geometry from plain arrays (no catalog).

        Args:
            objects: per object, in scene order: id, its boxes (B, 2, 3) min/max corners in the object
                frame, and its contact points name -> (position (3,) object frame, joint name).
        """
        centre, half, owner, counts = [], [], [], []
        c_owner, c_local, c_names, c_joints = [], [], [], []
        for i, (_, boxes, contacts) in enumerate(objects):
            b = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
            lo, hi = b.min(axis=1), b.max(axis=1)
            centre.append((lo + hi) / 2)
            half.append((hi - lo) / 2)
            owner.append(np.full(len(b), i))
            counts.append(len(b))
            for name in sorted(contacts):
                c_owner.append(i)
                c_local.append(np.asarray(contacts[name][0], dtype=np.float64))
                c_names.append(name)
                c_joints.append(contacts[name][1])
        return SceneGeometry(
            ids=tuple(o[0] for o in objects),
            box_centre=np.concatenate(centre) if centre else np.zeros((0, 3)),
            box_half=np.concatenate(half) if half else np.zeros((0, 3)),
            box_owner=np.concatenate(owner).astype(np.int64) if owner else np.zeros(0, np.int64),
            boxes_per_object=np.array(counts, dtype=np.int64),
            contact_owner=np.array(c_owner, dtype=np.int64),
            contact_local=np.array(c_local).reshape(-1, 3),
            contact_names=tuple(c_names),
            contact_joints=tuple(c_joints),
        )

    def contact_index(self, object_id: str, point: str, joint: str = "") -> int:
        """Index of an object's contact point (and joint, when it places several); ValueError if absent."""
        o = self.ids.index(object_id)
        for c in range(len(self.contact_names)):
            if (
                self.contact_owner[c] == o
                and self.contact_names[c] == point
                and joint in ("", self.contact_joints[c])
            ):
                return c
        known = sorted(
            {
                f"{self.contact_names[c]}:{self.contact_joints[c]}"
                for c in range(len(self.contact_names))
                if self.contact_owner[c] == o
            }
        )
        raise ValueError(
            f"object {object_id!r} has no contact point {point!r} for joint {joint or 'any'!r}; "
            f"it has {known}"
        )

    def object_contacts(self, object_id: str) -> list[int]:
        """Indices of all contact points of an object."""
        o = self.ids.index(object_id)
        return [c for c in range(len(self.contact_names)) if self.contact_owner[c] == o]


@dataclass(frozen=True)
class LayoutBatch:
    """K candidate layouts of the same O objects.

    Attributes:
        position: (K, O, 3) metres, world.
        yaw: (K, O) radians.
        scale: (K, O, 3).
    """

    position: np.ndarray
    yaw: np.ndarray
    scale: np.ndarray

    @staticmethod
    def from_scenes(scenes: list[Scene]) -> LayoutBatch:
        return LayoutBatch(
            position=np.array([[o.position for o in s.objects] for s in scenes], dtype=np.float64).reshape(
                len(scenes), -1, 3
            ),
            yaw=np.array([[o.yaw for o in s.objects] for s in scenes], dtype=np.float64).reshape(
                len(scenes), -1
            ),
            scale=np.array([[o.scale for o in s.objects] for s in scenes], dtype=np.float64).reshape(
                len(scenes), -1, 3
            ),
        )


def world_boxes(geom: SceneGeometry, layout: LayoutBatch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World oriented boxes for each layout.

    Returns:
        centre (K, B, 3), half extents (K, B, 3) along the owner's axes, yaw (K, B).
    """
    own = geom.box_owner
    scale = np.abs(layout.scale[:, own])  # (K, B, 3)
    yaw = layout.yaw[:, own]
    c, s = np.cos(yaw), np.sin(yaw)
    p = geom.box_centre[None] * scale
    centre = np.stack([c * p[..., 0] + s * p[..., 2], p[..., 1], -s * p[..., 0] + c * p[..., 2]], axis=-1)
    return centre + layout.position[:, own], geom.box_half[None] * scale, yaw


def contact_points_world(geom: SceneGeometry, layout: LayoutBatch, index: np.ndarray) -> np.ndarray:
    """(K, P, 3) world positions of the contact points ``index`` (P,) under each layout."""
    own = geom.contact_owner[index]
    p = geom.contact_local[index][None] * layout.scale[:, own]  # (K, P, 3) object frame, scaled
    yaw = layout.yaw[:, own]
    c, s = np.cos(yaw), np.sin(yaw)
    out = np.empty((layout.position.shape[0], len(index), 3))
    out[..., 0] = c * p[..., 0] + s * p[..., 2]
    out[..., 1] = p[..., 1]
    out[..., 2] = -s * p[..., 0] + c * p[..., 2]
    return out + layout.position[:, own]


@functools.lru_cache(maxsize=8)
def part_table(parts_bytes: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Sphere indices per body part, padded: (G, W) indices and (G, W) validity."""
    parts = np.frombuffer(parts_bytes, dtype=np.int64)
    members = [m for m in (np.flatnonzero(parts == g) for g in range(int(parts.max()) + 1)) if len(m)]
    width = max(len(m) for m in members)
    table = np.stack([np.pad(m, (0, width - len(m)), mode="edge") for m in members])
    valid = np.stack([np.arange(width) < len(m) for m in members])
    return table, valid


def body_part_bounds(
    centres: np.ndarray, radii: np.ndarray, parts: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(..., S, 3) sphere centres -> (..., G, 3) min and (..., G, 3) max corner of each part's spheres."""
    table, valid = part_table(np.asarray(parts, dtype=np.int64).tobytes())
    c = centres[..., table, :]  # (..., G, W, 3); padding repeats a member, so min/max are unaffected
    r = radii[table][..., None]
    return (c - r).min(axis=-2), (c + r).max(axis=-2)


def box_hits(
    centres: np.ndarray,
    radii: np.ndarray,
    box_centre: np.ndarray,
    box_half: np.ndarray,
    box_yaw: np.ndarray,
    tolerance: np.ndarray | None = None,
    parts: np.ndarray | None = None,
    part_bounds: tuple[np.ndarray, np.ndarray] | None = None,
    owner: np.ndarray | None = None,
) -> np.ndarray:
    """Which boxes the body hits in which frame.

    Args:
        centres: (K, T, S, 3) body sphere centres, world.
        radii: (S,) sphere radii.
        box_centre: (K, B, 3) world box centres.
        box_half: (K, B, 3) half extents along the box axes.
        box_yaw: (K, B) box yaw, radians.
        tolerance: (K, T, B) penetration depth (metres) allowed before a touch counts as a hit;
            None for none.
        parts: (S,) body part of each sphere, for the broad phase; None = one part.
        part_bounds: (K, T, G, 3) min and max corners of each part per frame, if already known.
        owner: (B,) object index of each box (boxes of an object contiguous), for an object-level
            broad phase; None to skip it.

    Returns:
        (K, T, B) bool, true where some sphere of frame t overlaps box b in layout k.
    """
    k_, t_, s_, _ = centres.shape
    b_ = box_centre.shape[1]
    hits = np.zeros((k_, t_, b_), dtype=bool)
    if b_ == 0 or t_ == 0 or s_ == 0:
        return hits
    parts = np.zeros(s_, dtype=np.int64) if parts is None else np.asarray(parts, dtype=np.int64)
    table, valid = part_table(parts.tobytes())
    if part_bounds is None:
        part_bounds = body_part_bounds(centres, radii, parts)
    lo, hi = part_bounds  # (K, T, G, 3)
    c, s = np.abs(np.cos(box_yaw)), np.abs(np.sin(box_yaw))
    ext = np.stack(
        [
            c * box_half[..., 0] + s * box_half[..., 2],
            box_half[..., 1],
            s * box_half[..., 0] + c * box_half[..., 2],
        ],
        axis=-1,
    )  # (K, B, 3) world AABB half
    box_lo, box_hi = box_centre - ext, box_centre + ext
    # Broad phase in three stages: body vs object, body vs box, part vs box.
    body_lo, body_hi = lo.min(axis=2), hi.max(axis=2)  # (K, T, 3)
    if owner is not None and len(owner) == b_ and b_ > 1:
        starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
        group = np.cumsum(np.r_[False, owner[1:] != owner[:-1]])
        obj_lo = np.minimum.reduceat(box_lo, starts, axis=1)
        obj_hi = np.maximum.reduceat(box_hi, starts, axis=1)  # (K, O', 3)
        near = np.all(
            (body_lo[:, :, None] <= obj_hi[:, None]) & (body_hi[:, :, None] >= obj_lo[:, None]), axis=-1
        )
        k, t, b = np.nonzero(near[:, :, group])
    else:
        k, t, b = np.nonzero(np.ones((k_, t_, b_), dtype=bool))
    keep = np.all((body_lo[k, t] <= box_hi[k, b]) & (body_hi[k, t] >= box_lo[k, b]), axis=-1)
    k, t, b = k[keep], t[keep], b[keep]
    if len(k) == 0:
        return hits
    part_ok = np.all(
        (lo[k, t] <= box_hi[k, b][:, None]) & (hi[k, t] >= box_lo[k, b][:, None]), axis=-1
    )  # (P, G)
    pi, g = np.nonzero(part_ok)
    if len(pi) == 0:
        return hits
    k, t, b = k[pi], t[pi], b[pi]
    idx = table[g]  # (P, W)
    d = centres[k[:, None], t[:, None], idx] - box_centre[k, b][:, None, :]  # (P, W, 3)
    cy, sy = np.cos(box_yaw[k, b])[:, None], np.sin(box_yaw[k, b])[:, None]
    lx = cy * d[..., 0] - sy * d[..., 2]  # world -> box frame: R_y(-yaw)
    lz = sy * d[..., 0] + cy * d[..., 2]
    half = box_half[k, b][:, None, :]
    ex = np.maximum(np.abs(lx) - half[..., 0], 0.0)
    ey = np.maximum(np.abs(d[..., 1]) - half[..., 1], 0.0)
    ez = np.maximum(np.abs(lz) - half[..., 2], 0.0)
    dist2 = ex * ex + ey * ey + ez * ez  # (P, W)
    reach = radii[idx]
    if tolerance is not None:
        reach = reach - tolerance[k, t, b][:, None]
    touch = np.any((dist2 < np.square(np.maximum(reach, 0.0))) & valid[g], axis=1)
    hits[k[touch], t[touch], b[touch]] = True
    return hits


def collision_cost(box_hit: np.ndarray, geom: SceneGeometry) -> np.ndarray:
    """Eq. 1 from per-box hits.

    Args:
        box_hit: (K, B) bool, box hit at any frame of the motion.
        geom: the scene's geometry (box owners, boxes per object).

    Returns:
        (K,) C_D in [0, 1].
    """
    n_obj = len(geom.ids)
    # Boxes of an object are contiguous: one bincount over (layout, owner) counts them all.
    k_idx, b_idx = np.nonzero(box_hit)
    hit_per_object = np.bincount(
        k_idx * n_obj + geom.box_owner[b_idx], minlength=box_hit.shape[0] * n_obj
    ).reshape(box_hit.shape[0], n_obj)
    share = hit_per_object / np.maximum(geom.boxes_per_object, 1)[None]
    touched = hit_per_object > 0
    return np.where(touched.any(axis=1), share.sum(axis=1) / np.maximum(touched.sum(axis=1), 1), 0.0)


def contact_distances(contact_world: np.ndarray, joint_mean: np.ndarray) -> np.ndarray:
    """(K, P, 3), (K, P, 3) -> (K, P) distance of each contact point to its joint's mean position."""
    return np.linalg.norm(contact_world - joint_mean, axis=-1)


def contact_cost(contact_world: np.ndarray, joint_mean: np.ndarray) -> np.ndarray:
    """Eq. 2: (K, P, 3), (K, P, 3) -> (K,) mean contact distance in metres (0 without contacts)."""
    if contact_world.shape[1] == 0:
        return np.zeros(contact_world.shape[0])
    return contact_distances(contact_world, joint_mean).mean(axis=1)


def total_cost(c_d: np.ndarray, c_t: np.ndarray, lambda_d: float = 1.0, lambda_t: float = 10.0) -> np.ndarray:
    """C = λ_D·C_D + λ_T·C_T."""
    return lambda_d * c_d + lambda_t * c_t


def joint_index(names: list[str] | tuple[str, ...]) -> np.ndarray:
    """Canonical joint names -> (P,) indices; raises ValueError for an unknown joint."""
    try:
        return np.array([JOINT_INDEX[n] for n in names], dtype=np.int64)
    except KeyError as exc:
        raise ValueError(
            f"unknown joint {exc.args[0]!r}; joints are wana.domain.skeleton.JOINT_NAMES"
        ) from exc


def sphere_centres(spheres: BodySpheres, positions: np.ndarray) -> np.ndarray:
    """(K, T, J, 3) joint positions -> (K, T, S, 3) sphere centres."""
    return spheres.centres(positions)
