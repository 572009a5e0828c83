"""The composed room as the checks see it: objects found by the name a sentence used, world collision boxes,
support surfaces and contact points, each computed once per check run.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cached_property, lru_cache

import numpy as np

from proto.motion_data import PropTrack
from proto.scene import PlacedObject, Scene
from wana.arrays import from_wire
from wana.assets import catalog, vocabulary
from wana.assets.geometry import build_mesh, voxel_boxes

THIN_M = 0.05  # metres: objects lower than this (rugs, mats) are walked on, not into
FINE_CELLS = 40  # cells along an object's longest side for the checks' collision boxes ...
FINE_PITCH_M = 0.02  # ... and the smallest cell edge


def base_id(object_id: str) -> str:
    """ "chair/2" (the second of "two chairs") and "chair#2" (a second mention) -> "chair"."""
    return object_id.split("/")[0].split("#")[0]


def display(word: str) -> str:
    """A name as a user reads it: "coffee_table#2" -> "coffee table", a context object "ctx_armchair" -> "armchair"."""
    return base_id(word).removeprefix("ctx_").replace("_", " ")


SMALL_M = 0.25  # metres: objects smaller than this in every direction are props, not furniture


class World:
    """One scene with the geometry the checks need, cached per object."""

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        self.room = scene.room
        self.by_id: dict[str, PlacedObject] = {o.id: o for o in scene.objects}
        self._boxes: dict[str, np.ndarray] = {}
        self._points: dict[str, dict[str, list[tuple[str, np.ndarray]]]] = {}
        self.poses: dict[str, np.ndarray] = {}  # object id -> (T, 4, 4) per frame, for the objects that move

    def follow(self, tracks: Sequence[PropTrack], frames: int) -> None:
        """Let the objects the motions carry move: each one's pose per frame, the track's while a hand holds
        it, its placement elsewhere (as the renderer draws it, services/render/scene_geometry.prop_track)."""
        from scipy.spatial.transform import Rotation  # scipy.spatial is not needed before the first check

        for t in tracks:
            placed = self.by_id.get(t.object_id)
            if placed is None:
                continue
            if placed.id not in self.poses:
                self.poses[placed.id] = np.tile(catalog.object_to_world(placed), (frames, 1, 1))
            a, b = max(0, t.start_frame), min(frames, t.end_frame)
            if b <= a:
                continue
            pos = np.asarray(from_wire(t.position), float)[a - t.start_frame : b - t.start_frame]
            rot = Rotation.from_quat(
                np.asarray(from_wire(t.rotation), float)[a - t.start_frame : b - t.start_frame]
            )
            pose = self.poses[placed.id]
            pose[a:b, :3, :3] = rot.as_matrix() @ np.diag(placed.scale)
            pose[a:b, :3, 3] = pos

    def open_values(self, object_id: str, frames: int) -> np.ndarray | None:
        """(frames,) how open an object's door, lid or fronts are on each frame (Scene.states, 0 shut to 1
        open), None when no sentence changes it (it stands as modelled)."""
        from wana.domain.object_state import STATEFUL

        placed = self.by_id.get(object_id)
        if placed is None or "open" not in STATEFUL.get(placed.category, {}):
            return None
        for t in self.scene.states:
            if t.object_id == object_id and t.state == "open" and t.frames:
                return np.interp(np.arange(frames), t.frames, t.values)
        return None

    def find(self, ref: str) -> list[PlacedObject]:
        """Objects a sentence's word refers to: the id itself, else its copies, else the category."""
        if not ref:
            return []
        if ref in self.by_id:
            return [self.by_id[ref]]
        same = [o for o in self.scene.objects if base_id(o.id) == base_id(ref)]
        if same:
            return same
        exact = [o for o in self.scene.objects if o.category == ref]
        if exact:
            return exact
        kind = base_id(ref)  # "a chair" is also the dining chair or the office chair the room has
        return [o for o in self.scene.objects if kind in _kinds(o.category)]

    def copies(self, node_id: str) -> list[PlacedObject]:
        """The placed objects of one SSG object node: "chair" and, for "two chairs", "chair/2"."""
        return [o for o in self.scene.objects if o.id == node_id or o.id.startswith(node_id + "/")]

    def boxes(self, placed: PlacedObject) -> np.ndarray:
        """(N, 2, 3) world collision boxes."""
        if placed.id not in self._boxes:
            try:
                self._boxes[placed.id] = np.asarray(catalog.world_collision_boxes(placed), float).reshape(
                    -1, 2, 3
                )
            except KeyError:  # a category the catalog does not know: nothing to collide with
                self._boxes[placed.id] = np.zeros((0, 2, 3))
        return self._boxes[placed.id]

    def contact_points(self, placed: PlacedObject) -> dict[str, list[tuple[str, np.ndarray]]]:
        """Interaction name -> [(joint, world xyz)] (the main joint first, then the extra ones)."""
        if placed.id not in self._points:
            try:
                asset = catalog.asset_for(placed)
            except KeyError:
                self._points[placed.id] = {}
                return {}
            out: dict[str, list[tuple[str, np.ndarray]]] = {}
            for name, cp in asset.contact_points.items():
                pairs = [(cp.joint, catalog.to_world(placed, np.asarray(cp.position, float)))]
                pairs += [(j, catalog.to_world(placed, np.asarray(p, float))) for j, p in cp.extra.items()]
                out[name] = pairs
            self._points[placed.id] = out
        return self._points[placed.id]

    @cached_property
    def solids(self) -> list[tuple[PlacedObject, np.ndarray, np.ndarray]]:
        """(object, its world boxes (N, 2, 3), their overall box (2, 3)) for every object a body can go into."""
        out = []
        for o in self.scene.objects:
            boxes = self.boxes(o)
            if not len(boxes):
                continue
            outer = np.stack([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])
            if outer[1, 1] - outer[0, 1] < THIN_M:
                continue
            if float(np.max(outer[1] - outer[0])) < SMALL_M:
                continue  # a can or a cup is no furniture: a shin brushing it is not a body inside furniture
            out.append((o, boxes, outer))
        return out

    @cached_property
    def surfaces(self) -> list[tuple[PlacedObject, float, np.ndarray, np.ndarray]]:
        """(object, world height, xz min (2,), xz max (2,)) of every support surface, as world rectangles."""
        out = []
        for o in self.scene.objects:
            try:
                surfs = catalog.world_support_surfaces(o)
            except KeyError:
                continue
            for height, corners in surfs:
                out.append((o, float(height), corners.min(axis=0), corners.max(axis=0)))
        return out

    def supports_chain(self, placed: PlacedObject) -> set[str]:
        """The object, what it rests on (down to the floor) and what rests on it."""
        out = {placed.id}
        ref = placed.support
        while ref and ref in self.by_id and ref not in out:
            out.add(ref)
            ref = self.by_id[ref].support
        grew = True
        while grew:
            more = {o.id for o in self.scene.objects if o.support in out} - out
            out |= more
            grew = bool(more)
        return out

    def inside_room(self, xz: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """(T,) whether each (T, 2) floor point is inside the room's walls (shrunk by margin)."""
        hw, hd = self.room.width / 2 - margin, self.room.depth / 2 - margin
        return (np.abs(xz[:, 0]) <= hw) & (np.abs(xz[:, 1]) <= hd)


@lru_cache(maxsize=512)
def fine_collision_boxes(category: str, attributes: tuple[tuple[str, str], ...], seed: int) -> np.ndarray:
    """(N, 2, 3) object-frame collision boxes on a finer grid than the catalog's.

    The catalog voxelises an object into at most 12 cells a side (a sofa's cells are 17 cm), which is right for
    the optimiser's cost but would call a foot 5 cm from a chair leg "inside" it; the checks voxelise the same
    parts again at FINE_CELLS a side. Imported objects (no parts) keep the catalog's boxes.
    """
    from wana.assets.catalog import REGISTRY, Builder, _params, normalize_attributes, run
    from wana.assets.importers.registry import imported_object

    if imported_object(category) is not None or category not in REGISTRY:
        return np.asarray(catalog.make_object(category, dict(attributes), seed).collision_boxes)
    attrs = normalize_attributes(category, dict(attributes))
    builder = Builder()
    run(REGISTRY[category], builder, _params(category, REGISTRY[category], attrs, seed))
    lo, hi = build_mesh(builder.parts).bounds
    shift = np.array([-(lo[0] + hi[0]) / 2.0, -lo[1], -(lo[2] + hi[2]) / 2.0])
    for part in builder.parts:
        part.translation = part.translation + shift
    bounds = np.stack([lo + shift, hi + shift])
    boxes = voxel_boxes(builder.parts, bounds, max_cells=FINE_CELLS, min_pitch=FINE_PITCH_M)
    boxes.setflags(write=False)
    return boxes


def point_box_distance(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Euclidean distance from each point to each box (0 inside).

    Args:
        points: (n, 3) metres.
        boxes: (N, 2, 3) min/max corners.

    Returns:
        (n, N) metres.
    """
    below = boxes[None, :, 0] - points[:, None]
    above = points[:, None] - boxes[None, :, 1]
    gap = np.maximum(np.maximum(below, above), 0.0)
    return np.sqrt(np.einsum("nkc,nkc->nk", gap, gap))


@lru_cache(maxsize=1024)
def _kinds(category: str) -> tuple[str, ...]:
    """What a category is an instance of (dining_chair -> chair, seat, furniture); () when unknown."""
    try:
        return tuple(vocabulary.hypernyms(category))
    except KeyError:
        return ()
