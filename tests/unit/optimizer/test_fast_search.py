"""The annealing's fast path scores like the reference scorer, and cleared walks re-plan collision-free."""

from __future__ import annotations

import numpy as np
import pytest

from proto.motion_data import Motion, Segment
from proto.optimizer import Interaction, OptimiseSettings
from proto.scene import PlacedObject, Room, Scene
from services.optimizer.annealing import optimise_interaction
from services.optimizer.collisions import BodyCollider
from services.optimizer.costs import LayoutBatch, SceneGeometry
from services.optimizer.resynthesis import anchored_motion_fn
from services.optimizer.scoring import InteractionScorer
from services.optimizer.shifted import ShiftedScorer, _CellTable
from wana.arrays import to_wire
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS

catalog = pytest.importorskip("wana.assets.catalog", reason="needs the asset catalog")

from services.optimizer.clearing import clearing_layouts  # noqa: E402
from services.optimizer.verify import optimise_and_verify  # noqa: E402
from wana.domain.routes import NoRouteError, plan_route  # noqa: E402

ROOM = Room(room_type="office", width=5.0, depth=5.0, height=3.0)
PI = float(np.pi)


def _a_pose(n: int) -> np.ndarray:
    """(n, J, 4) rotations with both arms lowered 80 degrees (a walking body, arms at the sides)."""
    rot = np.zeros((n, N_JOINTS, 4), dtype=np.float32)
    rot[..., 3] = 1.0
    for joint, sign in (("LeftArm", -1.0), ("RightArm", 1.0)):
        half = sign * np.radians(80) / 2
        rot[:, JOINT_INDEX[joint]] = [0.0, 0.0, np.sin(half), np.cos(half)]
    return rot


def _walk_then_sit(path: np.ndarray, seat: np.ndarray, fps: int = 30) -> Motion:
    """Walk the polyline ``path`` (W, 2) at 1.2 m/s, then sit 1 s at ``seat`` (3,)."""
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n_walk = max(2, int(np.ceil(s[-1] / 1.2 * fps)))
    t = np.linspace(0.0, s[-1], n_walk)
    walk = np.stack([np.interp(t, s, path[:, 0]), np.full(n_walk, 0.95), np.interp(t, s, path[:, 1])], axis=1)
    sit = np.tile(seat, (fps, 1))
    root = np.vstack([walk, sit]).astype(np.float32)
    return Motion(
        character="Eve",
        joint_names=list(JOINT_NAMES),
        root_position=to_wire(root),
        rotations=to_wire(_a_pose(len(root))),
        segments=[
            Segment(index=0, action="walk", start_frame=0, end_frame=n_walk),
            Segment(index=1, action="sit", start_frame=n_walk, end_frame=len(root)),
        ],
    )


def _desk_scene() -> tuple[Scene, Interaction, Motion]:
    scene = Scene(
        room=ROOM,
        objects=[
            PlacedObject(id="desk", category="desk", position=(0.0, 0.0, -0.9)),
            PlacedObject(id="chair", category="office_chair", position=(0.0, 0.0, -0.3), yaw=PI),
            PlacedObject(id="laptop", category="laptop", position=(0.0, 0.75, -0.95), support="desk"),
        ],
    )
    motion = _walk_then_sit(np.array([[1.8, 1.8], [0.0, -0.6]]), np.array([0.0, 0.6, -0.65]))  # into the desk
    return scene, Interaction(character="Eve", action="sit", targets=["chair"]), motion


def _near_layouts(scene: Scene, k: int, seed: int) -> LayoutBatch:
    base = LayoutBatch.from_scenes([scene] * k)
    rng = np.random.default_rng(seed)
    pos = base.position + rng.uniform(-0.15, 0.15, base.position.shape) * [1.0, 0.0, 1.0]
    scale = base.scale * rng.uniform(0.85, 1.15, base.scale.shape)
    return LayoutBatch(position=pos, yaw=base.yaw, scale=scale)


@pytest.mark.parametrize("coarse", [True, False])
def test_shifted_scores_equal_the_reference_scorer_on_the_materialised_motions(coarse):
    scene, inter, motion = _desk_scene()
    geom = SceneGeometry.from_scene(scene)
    scorer = InteractionScorer(
        scene, inter, geometry=geom, frame_stride=3, action_frames_max=6, coarse=coarse, ik_reach=True
    )
    fn = anchored_motion_fn(scene, motion, inter, geom)
    fast = ShiftedScorer(scorer, motion, LayoutBatch.from_scenes([scene]))
    layouts = _near_layouts(scene, 6, seed=1)
    got = fast.score(layouts, fn.shifts(layouts))
    want = scorer.score(layouts, fn.from_layouts(layouts))
    assert want.box_hit.any(), "the test layouts should collide somewhere"
    np.testing.assert_array_equal(got.box_hit, want.box_hit)
    np.testing.assert_array_equal(got.locomotion_box_hit, want.locomotion_box_hit)
    np.testing.assert_allclose(got.cost, want.cost, rtol=0, atol=1e-9)
    np.testing.assert_allclose(got.distances, want.distances, rtol=0, atol=1e-9)


def test_shifted_scorer_refuses_a_changed_yaw():
    scene, inter, motion = _desk_scene()
    scorer = InteractionScorer(scene, inter)
    fast = ShiftedScorer(scorer, motion, LayoutBatch.from_scenes([scene]))
    lay = LayoutBatch.from_scenes([scene])
    turned = LayoutBatch(lay.position, lay.yaw + 0.1, lay.scale)
    with pytest.raises(ValueError, match="yaw"):
        fast.score(turned, np.zeros((1, motion.root_position.shape[0], 3)))


def test_neighbourhood_table_gives_the_colliders_coarse_hits():
    scene, _, _ = _desk_scene()
    geom = SceneGeometry.from_scene(scene)
    collider = BodyCollider(geom)
    objects = [o for o in range(len(geom.ids)) if collider.grids[o] is not None]
    table = _CellTable(collider, objects)
    rng = np.random.default_rng(3)
    for i, o in enumerate(objects):
        lo, hi = collider.bounds[o]
        m = 400
        p = rng.uniform(lo - 0.15, hi + 0.15, (m, 3))
        rr = rng.uniform(0.03, 0.15, m)
        sc = rng.uniform(0.8, 1.2, (m, 3))
        p = p * sc
        kk = rng.integers(0, 3, m)
        ref_k, ref_b = collider._coarse_hits(
            collider.grids[o], int(collider.box_start[o]), kk, kk, p, rr, sc, 3
        )
        got_k, got_b = table.coarse(np.full(m, i), kk, p, rr, sc)
        assert len(ref_b) > 0
        assert set(zip(ref_k[:, 0].tolist(), ref_b.tolist(), strict=True)) == set(
            zip(got_k.tolist(), got_b.tolist(), strict=True)
        )


def test_the_fast_path_anneals_exactly_like_the_per_motion_path():
    scene, inter, motion = _desk_scene()
    geom = SceneGeometry.from_scene(scene)
    fn = anchored_motion_fn(scene, motion, inter, geom)

    def plain(s: Scene) -> Motion:  # the same surrogate without its fast-path attributes
        return fn(s)

    plain.from_layouts = fn.from_layouts  # type: ignore[attr-defined]
    st = OptimiseSettings(steps=25)
    a = optimise_interaction(scene, fn, inter, settings=st, steps=25, motion=motion, geometry=geom, seed=4)
    b = optimise_interaction(scene, plain, inter, settings=st, steps=25, motion=motion, geometry=geom, seed=4)
    np.testing.assert_allclose(a.cost_curve, b.cost_curve, rtol=0, atol=1e-9)
    assert a.scene == b.scene and a.after == b.after
    assert a.motion.root_position.data == b.motion.root_position.data


def _ring_scene() -> tuple[Scene, Interaction]:
    """A chair closed in by four boxes; the start is in front of it, beyond the front box."""
    objs = [PlacedObject(id="chair", category="chair", position=(0.0, 0.0, -1.0))]
    for i, (dx, dz) in enumerate([(0.0, 0.65), (0.65, 0.0), (0.0, -0.65), (-0.65, 0.0)]):
        objs.append(PlacedObject(id=f"box{i}", category="box", position=(dx, 0.0, -1.0 + dz), seed=i))
    return Scene(room=ROOM, objects=objs), Interaction(character="Eve", action="sit", targets=["chair"])


def _route_follower(start: np.ndarray, seat: np.ndarray):
    """A verifier that re-plans the walk by A* (straight through when there is no route)."""

    def synth(scene: Scene) -> Motion:
        try:
            route = plan_route(scene, start, seat[[0, 2]], radius=0.3, ignore={"chair"})
        except NoRouteError:
            route = np.array([start, seat[[0, 2]]])
        return _walk_then_sit(route, seat)

    return synth


def test_clearing_pushes_the_obstacle_off_the_walk_and_leaves_targets_alone():
    scene, inter = _ring_scene()
    geom = SceneGeometry.from_scene(scene)
    motion = _walk_then_sit(np.array([[0.0, 1.5], [0.0, -1.0]]), np.array([0.0, 0.5, -1.0]))
    rep = InteractionScorer(scene, inter, geometry=geom, frame_stride=1)
    walk_hits = rep.score_scenes([scene], [motion]).locomotion_box_hit[0]
    hit_ids = {geom.ids[o] for o in np.unique(geom.box_owner[walk_hits])}
    assert hit_ids == {"box0"}
    cands = clearing_layouts(scene, inter, motion, walk_hits, geom)
    assert cands == clearing_layouts(scene, inter, motion, walk_hits, geom)  # deterministic
    for cand in cands:
        moved = {o.id for o, p in zip(cand.objects, scene.objects, strict=True) if o.position != p.position}
        assert moved == {"box0"}
        box = next(o for o in cand.objects if o.id == "box0")
        assert box.position[1] == 0.0  # vertical position fixed
    # The first (smallest, overlap-free) push leaves the route's clearance between box and walk.
    first = next(o for o in cands[0].objects if o.id == "box0")
    assert abs(first.position[0]) > 0.3


def test_a_walk_through_a_ring_of_boxes_is_verified_collision_free_after_clearing():
    scene, inter = _ring_scene()
    seat = np.array([0.0, 0.55, -1.0])  # the chair's sit point (10 cm above its 0.45 m seat)
    start = np.array([0.0, 1.5])
    motion = _walk_then_sit(np.array([start, seat[[0, 2]]]), seat)  # straight through box0
    res = optimise_and_verify(
        scene,
        inter,
        motion,
        settings=OptimiseSettings(steps=20),
        verifier=_route_follower(start, seat),
    )
    assert res.search.before.locomotion_collided_boxes > 0
    assert res.made == "motion_service"
    assert res.after.locomotion_collided_boxes == 0
    chair = next(o for o in res.scene.objects if o.id == "chair")
    assert chair.position == scene.objects[0].position
