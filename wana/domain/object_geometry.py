"""Object geometry for collisions and routes, read from the asset catalog and cached per variant.

An object's pose is T(position) · R_y(yaw) · S(scale) (the catalog's ``object_to_world``). Under a
yaw-only rotation an object-frame box stays a box, so each collision box becomes an oriented box
in the world: centre, half extents and the object's yaw. The optimiser and the routes work on
those arrays; everything here is vectorised over boxes.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from proto.scene import PlacedObject, Scene
from wana.domain.routes import Footprints


def find_object(scene: Scene, ref: str) -> PlacedObject | None:
    """The object an action names: by id, else by base id ("chair" for "chair#2") or category; None if none.

    One rule for the motion planner and the orchestrator's slot book, so both resolve a name alike.
    """
    if not ref:
        return None
    for o in scene.objects:
        if o.id == ref:
            return o
    for o in scene.objects:
        if o.id.split("#")[0] == ref or o.category == ref:
            return o
    return None


class CatalogUnavailable(RuntimeError):
    """The asset catalog (wana.assets.catalog) cannot be imported."""


@dataclass(frozen=True)
class ObjectShape:
    """Object-frame geometry of one catalog variant (before scale).

    Attributes:
        boxes: (B, 2, 3) min and max corners of the collision boxes, metres, object frame.
        contact_names: interaction name of each contact (catalog ``contact_points`` key); an
            interaction that places several joints appears once per joint.
        contact_positions: (C, 3) contact point positions, metres, object frame.
        contact_joints: skeleton joint for each contact point.
        stand_point: (3,) where a character stands to use the object, object frame.
    """

    boxes: np.ndarray
    contact_names: tuple[str, ...]
    contact_positions: np.ndarray
    contact_joints: tuple[str, ...]
    stand_point: np.ndarray


def _catalog():  # noqa: ANN202 - module object
    try:
        from wana.assets import catalog
    except ImportError as exc:  # pragma: no cover - depends on the tree's state
        raise CatalogUnavailable(f"the asset catalog wana.assets.catalog is not available: {exc}") from exc
    return catalog


@functools.lru_cache(maxsize=512)
def _shape(category: str, attributes: tuple[tuple[str, str], ...], seed: int) -> ObjectShape:
    cat = _catalog()
    placed = PlacedObject(id="_", category=category, attributes=dict(attributes), seed=seed)
    asset = (
        cat.asset_for(placed)
        if hasattr(cat, "asset_for")
        else cat.make_object(category, dict(attributes), seed)
    )
    boxes = np.asarray(asset.collision_boxes, dtype=np.float64).reshape(-1, 2, 3)
    boxes = np.stack([boxes.min(axis=1), boxes.max(axis=1)], axis=1)
    contacts = dict(getattr(asset, "contact_points", {}) or {})
    names_: list[str] = []
    pos: list[np.ndarray] = []
    joints_: list[str] = []
    for name in sorted(contacts):
        cp = contacts[name]
        # One interaction may place several joints (typing: both hands); each is its own pair.
        for joint, p in [(str(cp.joint), cp.position), *sorted((getattr(cp, "extra", {}) or {}).items())]:
            names_.append(name)
            joints_.append(str(joint))
            pos.append(np.asarray(p, dtype=np.float64).reshape(3))
    positions = np.array(pos).reshape(-1, 3)
    joints = tuple(joints_)
    names = tuple(names_)
    stand = getattr(asset, "stand_point", None)
    stand_point = np.zeros(3) if stand is None else np.asarray(stand, dtype=np.float64).reshape(-1)[:3]
    if stand_point.shape[0] == 2:  # pragma: no cover - an x, z stand point
        stand_point = np.array([stand_point[0], 0.0, stand_point[1]])
    return ObjectShape(boxes, names, positions, joints, stand_point)


def object_shape(placed: PlacedObject) -> ObjectShape:
    """Cached object-frame geometry of a placed object's catalog variant."""
    return _shape(placed.category, tuple(sorted(placed.attributes.items())), int(placed.seed))


def pose_matrix(position: np.ndarray, yaw: float, scale: np.ndarray) -> np.ndarray:
    """(4, 4) object -> world transform T(position) · R_y(yaw) · S(scale)."""
    c, s = np.cos(yaw), np.sin(yaw)
    m = np.eye(4)
    m[:3, :3] = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]) * np.asarray(scale)[None, :]
    m[:3, 3] = position
    return m


def to_world_points(
    local: np.ndarray, position: np.ndarray, yaw: np.ndarray, scale: np.ndarray
) -> np.ndarray:
    """Object-frame points to world, batched over poses.

    Args:
        local: (P, 3) points, object frame.
        position: (..., 3) object positions.
        yaw: (...) yaws, radians.
        scale: (..., 3) scales.

    Returns:
        (..., P, 3) world points.
    """
    p = local[None] * np.asarray(scale)[..., None, :] if np.ndim(scale) > 1 else local * scale
    c, s = np.cos(yaw)[..., None], np.sin(yaw)[..., None]
    x = c * p[..., 0] + s * p[..., 2]
    z = -s * p[..., 0] + c * p[..., 2]
    out = np.stack([x, p[..., 1], z], axis=-1)
    return out + np.asarray(position)[..., None, :]


def world_obbs(placed: PlacedObject) -> tuple[np.ndarray, np.ndarray]:
    """Oriented world collision boxes of one object.

    Returns:
        centre (B, 3) metres world and half extents (B, 3) metres along the object's axes; the
        boxes' rotation is the object's yaw.
    """
    shape = object_shape(placed)
    scale = np.abs(np.asarray(placed.scale, dtype=np.float64))
    centre_local = shape.boxes.mean(axis=1)
    half = (shape.boxes[:, 1] - shape.boxes[:, 0]) / 2 * scale
    centre = to_world_points(
        centre_local, np.asarray(placed.position, dtype=np.float64), np.asarray(placed.yaw), scale
    )
    return centre.reshape(-1, 3), half


def scene_footprints(scene: Scene, *, ignore: set[str] | frozenset[str] = frozenset()) -> Footprints:
    """Floor footprints of every collision box in the scene, minus the ignored objects'."""
    centres, halves, yaws, owners = [], [], [], []
    for obj in scene.objects:
        if obj.id in ignore:
            continue
        c, h = world_obbs(obj)
        centres.append(c)
        halves.append(h)
        yaws.append(np.full(len(c), obj.yaw))
        owners.extend([obj.id] * len(c))
    if not centres:
        return Footprints.from_aabbs(np.zeros((0, 2, 3)))
    c, h = np.concatenate(centres), np.concatenate(halves)
    return Footprints(
        centre=c[:, [0, 2]],
        half=h[:, [0, 2]],
        yaw=np.concatenate(yaws),
        y_min=c[:, 1] - h[:, 1],
        y_max=c[:, 1] + h[:, 1],
        owner=tuple(owners),
    )
