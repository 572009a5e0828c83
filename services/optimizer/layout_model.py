"""The annealing's state space: per movable object an x, z offset and two scale factors, as layouts.

Objects resting on a moved object follow it (their offset in its frame is kept, scaled with it). A
layout is allowed when every object stays inside the room, no two objects' bounds come to intersect
that did not already, and every object resting on another keeps its footprint on its support's top
(a laptop slid toward the chair stays on the desk).
"""

from __future__ import annotations

import math

import msgspec
import numpy as np

from proto.scene import PlacedObject, Scene
from services.optimizer.costs import LayoutBatch

SUPPORT_SLACK_M = 0.02  # metres an object's footprint may poke out past its support's edge


def support_order(scene: Scene) -> list[int]:
    """Object indices with every support before the objects resting on it (cycles are cut)."""
    index = {o.id: i for i, o in enumerate(scene.objects)}
    order: list[int] = []
    state = [0] * len(scene.objects)  # 0 new, 1 visiting, 2 done

    def visit(i: int) -> None:
        if state[i]:
            return
        state[i] = 1
        parent = index.get(scene.objects[i].support)
        if parent is not None and state[parent] == 0:
            visit(parent)
        state[i] = 2
        order.append(i)

    for i in range(len(scene.objects)):
        visit(i)
    return order


class LayoutModel:
    """Maps annealing states (K, M, 4) = (dx, dz, horizontal scale, vertical scale) to layouts."""

    def __init__(self, scene: Scene, movable: list[str]) -> None:
        self.scene = scene
        ids = [o.id for o in scene.objects]
        self.movable = [m for m in movable if m in ids]
        self.movable_idx = np.array([ids.index(m) for m in self.movable], dtype=np.int64)
        self.base = LayoutBatch.from_scenes([scene])
        self.parent = np.array([ids.index(o.support) if o.support in ids else -1 for o in scene.objects])
        self.order = support_order(scene)
        # Each object's world footprint relative to its position, per unit of its own scale, for the room check.
        from wana.assets.catalog import world_bounds

        pos0 = self.base.position[0]

        def bounds(o: PlacedObject) -> np.ndarray:
            try:
                return world_bounds(o)
            except KeyError:  # not in the catalog (geometry given as arrays): treat it as a point
                return np.array([o.position, o.position], dtype=float)

        self.extent = (
            np.stack([bounds(o) for o in scene.objects]) - pos0[:, None, :] if ids else np.zeros((0, 2, 3))
        )
        self.extent = self.extent / self.base.scale[0][:, None, :]
        half_w, half_d = scene.room.width / 2 + 1e-3, scene.room.depth / 2 + 1e-3
        self.room_min = np.array([-half_w, -half_d])
        self.room_max = np.array([half_w, half_d])
        lo = pos0[:, [0, 2]] + self.extent[:, 0][:, [0, 2]] * self.base.scale[0][:, [0, 2]]
        hi = pos0[:, [0, 2]] + self.extent[:, 1][:, [0, 2]] * self.base.scale[0][:, [0, 2]]
        # Objects already poking out (a window set into its wall) may not go further out, nothing more.
        self.slack_lo = np.minimum(lo - self.room_min, 0.0)
        self.slack_hi = np.minimum(self.room_max - hi, 0.0)
        # Supported objects already overhanging their support (a wide monitor on a narrow shelf) may not
        # overhang further; the others may poke out by SUPPORT_SLACK_M at most.
        self.has_support = bool(np.any(self.parent >= 0))
        if self.has_support:
            child = np.flatnonzero(self.parent >= 0)
            blo, bhi = self._bounds(self.base)
            self.support_slack = np.maximum(self._support_overhang(blo, bhi, child)[0], SUPPORT_SLACK_M)

    def _bounds(self, layout: LayoutBatch) -> tuple[np.ndarray, np.ndarray]:
        lo = layout.position + self.extent[None, :, 0] * layout.scale
        hi = layout.position + self.extent[None, :, 1] * layout.scale
        return lo, hi

    def no_new_overlaps(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where no two objects' bounds intersect that did not already (an object and its support
        may touch)."""
        lo, hi = self._bounds(layout)
        inter = np.all(
            (lo[:, :, None] < hi[:, None, :] - 1e-3) & (lo[:, None, :] < hi[:, :, None] - 1e-3), axis=-1
        )
        if not hasattr(self, "_allowed"):
            blo, bhi = self._bounds(self.base)
            base = np.all(
                (blo[:, :, None] < bhi[:, None, :] - 1e-3) & (blo[:, None, :] < bhi[:, :, None] - 1e-3),
                axis=-1,
            )[0]
            n = len(self.parent)
            allowed = base | np.eye(n, dtype=bool)
            for i, p in enumerate(
                self.parent
            ):  # an object rests on its support, and on its support's support
                while p >= 0:
                    allowed[i, p] = allowed[p, i] = True
                    p = self.parent[p]
            self._allowed = allowed
        return ~np.any(inter & ~self._allowed[None], axis=(1, 2))

    def inside_room(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where every object of the layout stays inside the room (x and z)."""
        xz = layout.position[..., [0, 2]]
        scale = layout.scale[..., [0, 2]]
        lo = xz + self.extent[None, :, 0][..., [0, 2]] * scale
        hi = xz + self.extent[None, :, 1][..., [0, 2]] * scale
        ok = (lo - self.room_min >= self.slack_lo - 1e-9) & (self.room_max - hi >= self.slack_hi - 1e-9)
        return np.all(ok, axis=(1, 2))

    def on_supports(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where every object resting on another keeps its x, z footprint on its support's
        (to within SUPPORT_SLACK_M, or no further off than it already was)."""
        if not self.has_support:
            return np.ones(layout.position.shape[0], dtype=bool)
        child = np.flatnonzero(self.parent >= 0)
        lo, hi = self._bounds(layout)
        over = self._support_overhang(lo, hi, child)
        return np.all(over <= self.support_slack[None] + 1e-9, axis=(1, 2))

    def _support_overhang(self, lo: np.ndarray, hi: np.ndarray, child: np.ndarray) -> np.ndarray:
        """(K, C, 4) metres each supported object's footprint pokes out of its support's, per side."""
        par = self.parent[child]
        xz = [0, 2]
        return np.concatenate(
            [lo[:, par][..., xz] - lo[:, child][..., xz], hi[:, child][..., xz] - hi[:, par][..., xz]],
            axis=-1,
        )

    def allowed(self, layout: LayoutBatch) -> np.ndarray:
        """(K,) True where a layout keeps every rule: inside the room, no new overlap, on its support."""
        return self.inside_room(layout) & self.no_new_overlaps(layout) & self.on_supports(layout)

    def identity(self) -> np.ndarray:
        """(M, 4) the state of the input layout."""
        s = np.zeros((len(self.movable), 4))
        s[:, 2:] = 1.0
        return s

    def layouts(self, states: np.ndarray) -> LayoutBatch:
        """(K, M, 4) states -> K layouts."""
        k_ = states.shape[0]
        p0, yaw, s0 = self.base.position[0], self.base.yaw[0], self.base.scale[0]
        own = np.zeros((k_, len(p0), 4))
        own[..., 2:] = 1.0
        own[:, self.movable_idx] = states
        pos = np.empty((k_, len(p0), 3))
        scale = s0[None] * np.stack([own[..., 2], own[..., 3], own[..., 2]], axis=-1)
        for i in self.order:
            par = self.parent[i]
            shift = np.stack([own[:, i, 0], np.zeros(k_), own[:, i, 1]], axis=-1)
            if par < 0:
                pos[:, i] = p0[i] + shift
                continue
            # Keep the offset from the support fixed in the support's frame, scaled with it.
            c, s = math.cos(yaw[par]), math.sin(yaw[par])
            d = p0[i] - p0[par]
            local = np.array([c * d[0] - s * d[2], d[1], s * d[0] + c * d[2]])
            local = local[None] * (scale[:, par] / s0[par])
            world = np.stack(
                [c * local[:, 0] + s * local[:, 2], local[:, 1], -s * local[:, 0] + c * local[:, 2]], -1
            )
            pos[:, i] = pos[:, par] + world + shift
        return LayoutBatch(position=pos, yaw=np.repeat(yaw[None], k_, axis=0), scale=scale)

    def scene_at(self, layout: LayoutBatch, k: int) -> Scene:
        """The Scene of layout k (only changed objects are rebuilt)."""
        objs = []
        for i, o in enumerate(self.scene.objects):
            p = tuple(float(v) for v in layout.position[k, i])
            s = tuple(float(v) for v in layout.scale[k, i])
            objs.append(
                o
                if (p == tuple(o.position) and s == tuple(o.scale))
                else msgspec.structs.replace(o, position=p, scale=s)
            )
        return msgspec.structs.replace(self.scene, objects=objs)
