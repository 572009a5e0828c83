"""Legroom: furniture the seated body sits inside (legs in a desk's drawer pedestal) slides sideways off
it, the laptop on it stays where the hands are (real catalog, real motion service)."""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.optimizer import Interaction
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode
from services.motion.seated import seated_action_fn
from services.optimizer.costs import SceneGeometry
from services.optimizer.legroom import legroom_layouts, seated_hits
from services.optimizer.scoring import InteractionScorer

# The office example's layout after the typing optimisation pulled the desk toward the chair: Eve's
# right leg goes into the desk's drawer pedestal while she types.
ROOM = Room(room_type="office", width=4.71, depth=4.095, height=2.7)
PI = float(np.pi)
OFFICE = Scene(
    room=ROOM,
    objects=[
        PlacedObject(
            id="desk", category="desk", seed=891, position=(-0.302, 0.0, 1.395), yaw=-PI,
            scale=(1.0194, 1.0237, 1.0194),
        ),
        PlacedObject(
            id="laptop", category="laptop", seed=927, position=(-0.4486, 0.7406, 1.3857), yaw=-PI,
            support="desk",
        ),
        PlacedObject(
            id="chair", category="chair", seed=474, position=(-0.3942, 0.0, 0.7807),
            scale=(0.9027, 0.9761, 0.9027),
        ),
    ],
)  # fmt: skip
SEATED_TYPE = Interaction(character="Eve", action="type", targets=["chair", "laptop"])
TYPE = ActionNode(verb="type", action="type", target="laptop", duration_s=3.0)


@pytest.fixture(scope="module")
def typing():
    resynthesise = seated_action_fn("Eve", "chair", TYPE)
    scorer = InteractionScorer(OFFICE, SEATED_TYPE, frame_stride=1, geometry=SceneGeometry.from_scene(OFFICE))
    return resynthesise, scorer, resynthesise(OFFICE)


def _desk_hits(scorer: InteractionScorer, scene: Scene, motion) -> int:
    return int(seated_hits(scorer, scene, motion)[scorer.geom.ids.index("desk")])


def test_the_seated_legs_are_inside_the_desk_in_the_pulled_layout(typing):
    _, scorer, motion = typing
    hits = seated_hits(scorer, OFFICE, motion)
    assert _desk_hits(scorer, OFFICE, motion) >= 8
    assert hits[scorer.geom.ids.index("chair")] == 0  # the seat is a target: sitting on it is contact


def test_the_desk_slides_sideways_and_the_laptop_stays_where_the_hands_are(typing):
    _, scorer, motion = typing
    layouts = legroom_layouts(OFFICE, SEATED_TYPE, motion, scorer)
    assert layouts
    moved = {
        o.id: np.subtract(o.position, p.position)
        for o, p in zip(layouts[0].objects, OFFICE.objects, strict=True)
    }
    assert abs(moved["desk"][0]) >= 0.05 and abs(moved["desk"][2]) < 1e-9  # sideways only
    assert np.allclose(moved["laptop"], 0.0, atol=1e-9) and np.allclose(moved["chair"], 0.0)


def test_the_resynthesised_typing_in_the_slid_layout_clears_the_desk_and_keeps_the_keys(typing):
    resynthesise, scorer, motion = typing
    before = scorer.score_scenes([OFFICE], [motion]).report(0, scorer.pairs)
    cand = legroom_layouts(OFFICE, SEATED_TYPE, motion, scorer)[0]
    real = resynthesise(cand)
    after = scorer.score_scenes([cand], [real]).report(0, scorer.pairs)
    assert _desk_hits(scorer, cand, real) < _desk_hits(scorer, OFFICE, motion) / 2
    assert after.collided_boxes < before.collided_boxes
    assert max(after.contact_distances[1:]) < 0.05  # both hands on the laptop's keys


def test_a_body_that_hits_nothing_gets_no_legroom_layouts(typing):
    resynthesise, scorer, _ = typing
    # The desk pushed back to the wall and the laptop slid to its front edge (what the optimiser now
    # returns for the office example): the legs are in front of the desk.
    desk, laptop, chair = OFFICE.objects
    far = Scene(
        room=ROOM,
        objects=[
            msgspec.structs.replace(desk, position=(-0.3017, 0.0, 1.6955)),
            msgspec.structs.replace(laptop, position=(-0.4484, 0.7406, 1.4843)),
            chair,
        ],
    )
    far_scorer = InteractionScorer(far, SEATED_TYPE, frame_stride=1)
    motion = resynthesise(far)
    assert not seated_hits(far_scorer, far, motion).any()
    assert legroom_layouts(far, SEATED_TYPE, motion, far_scorer) == []


def test_legroom_moves_nothing_outside_an_explicit_movable_list(typing):
    _, scorer, motion = typing
    only_chair = Interaction(character="Eve", action="type", targets=["chair", "laptop"], movable=["chair"])
    assert legroom_layouts(OFFICE, only_chair, motion, scorer) == []
