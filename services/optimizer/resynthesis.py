"""How the motion follows a changed layout: the motion service itself, or a fast anchored surrogate.

``motion_service_fn`` re-plans and re-synthesises the character's whole plan through the motion
service's logic (its planning and synthesis, installed in ``motion_port`` by the composition root,
with A* routes from wana.domain.routes), which is faithful and slow (a few hundred ms per call).

``anchored_motion_fn`` keeps the given motion and moves it with the object it is anchored to (the
interaction's first target): from the action's start on, the root follows the anchor's contact
point; over the walk that approaches it, the shift ramps in smoothly. That is what re-synthesis
does to the root when nothing else changes, at the cost of one array operation per proposal, so
annealing can score hundreds of proposals inside the bench's budget. The optimiser anneals with the
surrogate and verifies the winning layout with the motion service (see handlers.optimise).
"""

from __future__ import annotations

from collections.abc import Callable

import msgspec
import numpy as np

from proto.motion_data import Motion
from proto.optimizer import ContactPair, Interaction
from proto.scene import Scene
from proto.ssg import CharacterNode
from services.optimizer.body import motion_joint_positions, remember_joint_positions
from services.optimizer.contacts import default_contacts
from services.optimizer.costs import LayoutBatch, SceneGeometry, contact_points_world
from services.optimizer.motion_port import MotionSynthesis, installed
from services.optimizer.scoring import action_segment, is_locomotion
from wana.arrays import from_wire, to_wire
from wana.domain.actions import contact_targets
from wana.domain.routes import NoRouteError, plan_route

MotionFn = Callable[[Scene], Motion]


def motion_service_fn(
    character: CharacterNode,
    start: tuple[float, float, float],
    *,
    radius: float = 0.3,
    synthesis: MotionSynthesis | None = None,
) -> MotionFn:
    """scene -> Motion through the motion service (plan + synthesis), routes by A*.

    Where no route exists the character walks the straight line, through whatever blocks it, so
    that the blocked walk shows up as collisions instead of an error.

    Args:
        character: the SSG character whose actions make the motion.
        start: (x, z, yaw) where the character starts.
        radius: clearance of the routes, metres: the body's 0.25 m plus room for swinging arms and
            for the walk's deviation from its path.
        synthesis: the motion service's functions; None: the ones the composition root installed.

    Raises:
        MotionSynthesisMissing: synthesis is None and none was installed.
    """
    character_motion = (synthesis or installed()).character_motion

    def route(scene: Scene, a: tuple[float, float], b: tuple[float, float]) -> np.ndarray:
        try:
            return plan_route(scene, np.asarray(a), np.asarray(b), radius=radius)
        except NoRouteError:
            # Walk straight through: the collisions it causes are what the optimiser then removes.
            return np.array([a, b], dtype=np.float64)

    def motion_fn(scene: Scene) -> Motion:
        return character_motion(character, scene, start, route)

    return motion_fn


def planned_contacts(character: CharacterNode, scene: Scene) -> list[ContactPair]:
    """The contact pairs the motion service aims at for a character's actions (object, point, joint).

    The motion service picks, per action, one contact point of the target object (its preferred
    names for the clip's kind of interaction) and brings the clip's contact joints to it; C_T should
    measure those same pairs.
    """
    from wana.assets.catalog import asset_for
    from wana.domain.actions import get_clip

    by_id = {o.id: o for o in scene.objects}
    pairs: list[ContactPair] = []
    for node in character.actions:
        obj = by_id.get(node.target or node.instrument or node.destination)
        try:
            clip = get_clip(node.action or node.verb)
        except KeyError:
            continue
        if obj is None or clip.interaction is None:
            continue
        asset = asset_for(obj)
        points = {
            name: [
                (cp.joint, np.asarray(cp.position, float)),
                *[(j, np.asarray(p, float)) for j, p in cp.extra.items()],
            ]
            for name, cp in asset.contact_points.items()
        }
        chosen = contact_targets(clip, points)
        for name, lst in points.items():
            if {j for j, _ in lst} == set(chosen) and all(np.allclose(chosen[j], p) for j, p in lst):
                pairs += [ContactPair(object_id=obj.id, point=name, joint=j) for j, _ in lst]
                break
    return pairs


def approach_start(motion: Motion, action_start: int) -> int:
    """First frame of the run of locomotion segments that ends where the action starts."""
    start = action_start
    for seg in sorted(motion.segments, key=lambda s: s.start_frame, reverse=True):
        if seg.end_frame <= start and seg.end_frame >= start - 1 and is_locomotion(seg.action):
            start = seg.start_frame
    return start


def anchored_motion_fn(
    scene: Scene, motion: Motion, interaction: Interaction, geometry: SceneGeometry | None = None
) -> MotionFn:
    """scene -> the given motion moved with its anchor object (the interaction's first target).

    Args:
        scene: the layout the motion was made in.
        motion: the motion.
        interaction: its first target is the anchor; without targets the motion never moves.
        geometry: the scene's object geometry (read from the catalog when None).

    Returns:
        A motion_fn for optimise_interaction; scenes must hold the same objects as ``scene``.
    """
    if not interaction.targets:
        return lambda _scene: motion
    geom = geometry if geometry is not None else SceneGeometry.from_scene(scene)
    anchor = geom.ids.index(interaction.targets[0])
    pairs = [
        p
        for p in (interaction.contacts or default_contacts(geom, interaction))
        if p.object_id == interaction.targets[0]
    ]
    point = np.array([geom.contact_index(p.object_id, p.point, p.joint) for p in pairs[:1]], dtype=np.int64)
    root0 = from_wire(motion.root_position).astype(np.float64)
    positions0 = motion_joint_positions(motion)
    t_ = len(root0)
    a0, _ = action_segment(motion, interaction, t_)
    s0 = approach_start(motion, a0)
    frames = np.arange(t_)
    u = np.clip((frames - s0) / max(a0 - s0, 1), 0.0, 1.0) if a0 > s0 else (frames >= a0).astype(np.float64)
    w_xz = u * u * (3.0 - 2.0 * u)  # smoothstep in over the approach, 1 from the action on
    # Height follows the anchor only for a seat (hips on it) and only while the action holds.
    seated = bool(len(point)) and geom.contact_joints[int(point[0])] == "Hips"
    w_y = (frames >= a0).astype(np.float64) * seated
    base = LayoutBatch.from_scenes([scene])
    ref = _anchor_point(geom, base, anchor, point)

    def moved_by(d: np.ndarray) -> Motion:
        if not np.any(d):
            return motion
        shift = np.stack([w_xz * d[0], w_y * d[1], w_xz * d[2]], axis=1)  # (T, 3)
        root = (root0 + shift).astype(np.float32)
        moved = msgspec.structs.replace(motion, root_position=to_wire(root))
        delta = root.astype(np.float64) - root0
        remember_joint_positions(moved, positions0 + delta[:, None, :], base=positions0, shift=delta)
        return moved

    def motion_fn(new_scene: Scene) -> Motion:
        return moved_by(_anchor_point(geom, LayoutBatch.from_scenes([new_scene]), anchor, point)[0] - ref[0])

    def from_layouts(layouts: LayoutBatch) -> list[Motion]:
        d = _anchor_point(geom, layouts, anchor, point) - ref  # (K, 3)
        return [moved_by(dk) for dk in d]

    def shifts(layouts: LayoutBatch) -> np.ndarray:
        """(K, T, 3) per-frame translation of the root (as stored, float32-rounded) in each layout."""
        d = _anchor_point(geom, layouts, anchor, point) - ref  # (K, 3)
        shift = np.stack([w_xz * d[:, :1], w_y * d[:, 1:2], w_xz * d[:, 2:]], axis=-1)  # (K, T, 3)
        return (root0[None] + shift).astype(np.float32).astype(np.float64) - root0[None]

    motion_fn.from_layouts = from_layouts  # type: ignore[attr-defined]  # batch path used by the annealing
    # The fast path: proposals scored as shifts of `base_motion` (services.optimizer.shifted).
    motion_fn.shifts = shifts  # type: ignore[attr-defined]
    motion_fn.base_motion = motion  # type: ignore[attr-defined]
    return motion_fn


def _anchor_point(geom: SceneGeometry, layout: LayoutBatch, anchor: int, point: np.ndarray) -> np.ndarray:
    """(K, 3) world position of the anchor's first contact point, or of the anchor itself without one."""
    if len(point):
        return contact_points_world(geom, layout, point)[:, 0]
    return layout.position[:, anchor].copy()
