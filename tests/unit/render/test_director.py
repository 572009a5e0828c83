"""The director: shots per sentence, every shot type shows its subject, the 180° rule, command scoping,
cut-away walls and the shots in the export.

Characters stand (walk on the spot) at known places in an empty room, with segments that say what
they do in which sentence, so the expected shots follow from the rules in services.render.director.
"""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.common import Header
from proto.motion_data import Motion, Segment
from proto.render import ExportRequest, TimedCommand
from proto.scene import Room, Scene
from proto.ssg import Command
from services.render.camera import CameraKey, camera_at, project
from services.render.coverage import Coverage
from services.render.demo import walk_motion
from services.render.director import MIN_SHOT_FRAMES, Scorer, plan_shots, shot_keys
from services.render.framing import Adjust
from services.render.handlers import handle_export
from services.render.renderer import FrameRenderer
from services.render.staging import Staging

ROOM = Room(room_type="living_room", width=6.0, depth=5.0, height=2.8)
SCENE = Scene(room=ROOM, objects=[], seed=0)


def actor(name: str, x: float, z: float, n: int, acts: list[tuple[str, int, int, str]]) -> Motion:
    """A character standing at (x, z) for n frames doing (action, start, end, sentence id)."""
    m = walk_motion(name, (x, z), (x, z), n, expression="none")
    segs = [
        Segment(index=i, action=a, start_frame=s, end_frame=e, sentence_id=sid)
        for i, (a, s, e, sid) in enumerate(acts)
    ]
    return msgspec.structs.replace(m, segments=segs)


@pytest.fixture(scope="module")
def pair() -> list[Motion]:
    """Eve and Tom 1.4 m apart talking in turns, then hugging."""
    eve = actor(
        "Eve", -0.7, 0.2, 240, [("talk", 0, 60, "s1"), ("talk", 120, 180, "s3"), ("hug", 180, 240, "s4")]
    )
    tom = actor("Tom", 0.7, -0.2, 240, [("talk", 60, 120, "s2"), ("hug", 180, 240, "s4")])
    return [eve, tom]


@pytest.fixture(scope="module")
def staged(pair: list[Motion]) -> Staging:
    return Staging.build(SCENE, pair)


@pytest.mark.parametrize("mode", ["wide", "medium", "tracking", "close_up", "two_shot", "over_shoulder"])
def test_every_shot_type_shows_its_subject_in_frame(staged: Staging, mode: str) -> None:
    key = CameraKey(frame=0, mode=mode, character="Eve", partner="Tom", adjust=Adjust(), end=240)
    cover = Coverage.from_rigs(staged.rigs, SCENE)
    frames = [10, 100, 200]
    poses = [camera_at(f, [key], staged.tracks, ROOM) for f in frames]
    who = ["Eve", "Tom"] if mode in ("wide", "two_shot") else ["Eve"]
    assert cover.shown(poses, frames, who) == 1.0
    if mode == "over_shoulder":  # over Tom's shoulder: Tom is nearer the lens than Eve
        eye = poses[0].eye
        assert np.linalg.norm(eye - staged.tracks["Tom"].hips[10]) < np.linalg.norm(
            eye - staged.tracks["Eve"].hips[10]
        )


def test_a_conversation_cuts_between_speakers_on_one_side_of_the_line(staged: Staging) -> None:
    shots = staged.shots
    assert shots[0].kind == "wide" and shots[0].start == 0  # the establishing shot on the first action
    assert [s.start for s in shots[1:]] == [60, 120, 180]  # cuts on sentence boundaries
    assert [(s.kind, s.subject) for s in shots[1:]] == [
        ("over_shoulder", "Tom"),
        ("over_shoulder", "Eve"),
        ("two_shot", "Eve"),
    ]
    eve, tom = staged.tracks["Eve"].hips[100], staged.tracks["Tom"].hips[100]
    line = (tom - eve)[[0, 2]]
    sides = []
    for s in shots[1:]:
        eye = staged.camera((s.start + s.end) // 2).eye
        rel = (eye - eve)[[0, 2]]
        sides.append(np.sign(line[0] * rel[1] - line[1] * rel[0]))
    assert len(set(sides)) == 1 and sides[0] != 0  # the 180° rule: never across the line Eve-Tom


def test_no_shot_is_shorter_than_a_second_and_a_half_and_no_two_in_a_row_frame_alike() -> None:
    eve = actor(
        "Eve",
        0.0,
        0.0,
        200,
        [("wave", 0, 20, "s1"), ("nod", 20, 40, "s2"), ("clap", 40, 120, "s3"), ("point", 120, 200, "s4")],
    )
    stage = Staging.build(SCENE, [eve])
    lengths = [s.end - s.start for s in stage.shots]
    assert min(lengths) >= MIN_SHOT_FRAMES
    for a, b in zip(stage.shots, stage.shots[1:], strict=False):
        assert (a.kind, a.subject) != (b.kind, b.subject)


def test_close_with_a_subject_lasts_until_its_next_action_ends_then_the_director_resumes() -> None:
    eve = actor("Eve", -1.5, 0.0, 300, [("walk", 0, 60, "s1"), ("talk", 200, 300, "s5")])
    tom = actor("Tom", 1.5, 0.0, 300, [("wave", 60, 130, "s3"), ("clap", 130, 200, "s4")])
    close = TimedCommand(
        frame=60, command=Command(kind="camera", value="close", target="Tom"), sentence_id="s2"
    )
    stage = Staging.build(SCENE, [eve, tom], [close])
    commanded = [s for s in stage.shots if s.source == "command"]
    assert [(s.kind, s.subject, s.start, s.end) for s in commanded] == [("close", "Tom", 60, 130)]
    after = [s for s in stage.shots if s.start >= 130]
    assert after and all(s.source == "director" for s in after)
    assert any(s.subject == "Eve" for s in after)  # Eve's talk is not left off-screen


def test_a_view_command_holds_until_the_next_camera_command() -> None:
    eve = actor("Eve", -1.0, 0.0, 300, [("walk", 0, 60, "s1"), ("talk", 200, 300, "s5")])
    tom = actor("Tom", 1.0, 0.0, 300, [("wave", 60, 200, "s3")])
    cmds = [
        TimedCommand(
            frame=60,
            command=Command(kind="camera", value="left", target="Eve"),
            sentence_id="s2",
            implied_target=True,
        ),
        TimedCommand(frame=250, command=Command(kind="camera", value="wide"), sentence_id="s4b"),
    ]
    stage = Staging.build(SCENE, [eve, tom], cmds)
    spans = [(s.kind, s.subject, s.start, s.end) for s in stage.shots if s.start >= 60]
    assert spans == [("left", "Tom", 60, 200), ("left", "Eve", 200, 250), ("wide", "", 250, 300)]
    hips, facing, _ = stage.tracks["Tom"].smoothed(60)
    left = np.array([facing[2], 0.0, -facing[0]])
    assert float((stage.camera(150).eye - hips) @ left) > 1.0  # on Tom's left while he waves


def test_walls_between_the_camera_and_the_room_are_cut_away_in_the_picture() -> None:
    eve = actor("Eve", 0.0, 1.5, 30, [("wave", 0, 30, "s1")])
    key = [CameraKey(frame=0, mode="wide", adjust=Adjust(), end=30)]
    stage = Staging.build(SCENE, [eve])
    pose = camera_at(5, key, stage.tracks, ROOM)
    assert pose.eye[2] > ROOM.depth / 2  # the establishing camera stands behind the front wall
    with_eve = FrameRenderer(SCENE, [eve], width=160, height=120)
    empty = FrameRenderer(SCENE, [], n_frames=30, width=160, height=120)
    try:
        a, b = with_eve.render(5, pose=pose), empty.render(5, pose=pose)
    finally:
        with_eve.close()
        empty.close()
    uv, z = project(stage.rigs["Eve"].joint_positions[5, :1] + np.array([0.0, 0.3, 0.0]), pose, 160, 120)
    u, v = np.clip(uv[0].round().astype(int), 0, [159, 119])
    assert z[0] > 0 and np.abs(a[v, u].astype(int) - b[v, u].astype(int)).sum() > 30  # Eve, not a wall


def test_the_export_reply_lists_the_shots(pair: list[Motion]) -> None:
    req = ExportRequest(header=Header(), format="mp4", scene=SCENE, motions=pair, width=160, height=120)
    reply = handle_export(req)
    shots = [(s.start_frame, s.end_frame, s.type, s.subject) for s in reply.shots]
    assert shots[0][:3] == (0, 60, "wide") and shots[-1][1] == reply.n_frames
    assert all(a[1] == b[0] for a, b in zip(shots, shots[1:], strict=False))  # every frame in one shot


class _SouthThenNorth(Scorer):
    """Prefers cameras south of the pair (z > 0) before frame 120 and north of it after: a room whose
    free views change side mid-conversation."""

    def shown(self, poses, frames, who) -> float:  # noqa: ANN001
        return float(self.shown_each(poses, frames, who).mean())

    def shown_each(self, poses, frames, who) -> np.ndarray:  # noqa: ANN001
        seen = [(p.eye[2] > 0) == (f < 120) for p, f in zip(poses, frames, strict=True)]
        return np.repeat(np.array(seen, dtype=bool)[:, None], len(who), axis=1)


def test_the_pair_keeps_its_side_even_where_the_other_side_would_see_better(staged: Staging) -> None:
    shots = plan_shots(staged.motions, staged.tracks, [], staged.n_frames, ROOM, _SouthThenNorth())
    pairs = [s for s in shots if s.partner]
    assert len(pairs) >= 2 and len({s.side for s in pairs}) == 1
    # where the kept side sees worse, the pair is not crossed but seen in a wide shot (a neutral view)
    assert all(s.partner or s.kind == "wide" for s in shots)
    assert staged.tracks["Eve"].hips[0][2] > staged.tracks["Tom"].hips[0][2]  # the line is not along x
    singles = plan_shots(staged.motions, staged.tracks, [], staged.n_frames, ROOM, _SouthThenNorth())
    assert singles == shots  # planning is a pure function of its inputs


def test_a_close_up_of_tom_cuts_away_when_eve_begins_a_sentence_in_its_scope() -> None:
    eve = actor("Eve", -1.5, 0.0, 300, [("walk", 0, 60, "s1"), ("wave", 150, 300, "s4")])
    tom = actor("Tom", 1.5, 0.0, 300, [("clap", 60, 300, "s3")])  # his next action outlasts Eve's wave
    close = TimedCommand(
        frame=60, command=Command(kind="camera", value="close", target="Tom"), sentence_id="s2"
    )
    stage = Staging.build(SCENE, [eve, tom], [close])
    commanded = [(s.kind, s.subject, s.start, s.end) for s in stage.shots if s.source == "command"]
    assert commanded == [("close", "Tom", 60, 150)]  # in force 3 s, then Eve's wave is shown
    assert any("Eve" in (s.subject, s.partner, *s.acting) for s in stage.shots if s.start >= 150)


def test_a_close_up_held_shorter_than_a_shot_still_shows_for_the_minimum_shot_length() -> None:
    eve = actor("Eve", -1.5, 0.0, 300, [("wave", 70, 300, "s4")])
    tom = actor("Tom", 1.5, 0.0, 300, [("walk", 0, 60, "s1"), ("clap", 60, 300, "s3")])
    close = TimedCommand(
        frame=60, command=Command(kind="camera", value="close", target="Tom"), sentence_id="s2"
    )
    stage = Staging.build(SCENE, [eve, tom], [close])
    commanded = [(s.start, s.end) for s in stage.shots if s.source == "command"]
    assert commanded == [(60, 60 + MIN_SHOT_FRAMES)]


def test_the_commanded_close_up_shows_its_subject_head_to_knees() -> None:
    from services.render.camera_checks import camera_checks

    tom = actor("Tom", 1.0, 0.0, 120, [("clap", 0, 120, "s2")])
    cmds = [("s1", Command(kind="camera", value="close", target="Tom"))]
    sentences = [("s1", "camera close on Tom"), ("s2", "Tom claps.")]
    checks = camera_checks(SCENE, [tom], cmds, sentences, width=320, height=240)
    [check] = [c for c in checks["s2"] if c.name == "in_view"]
    assert check.ok, check.reason
    stage = Staging.build(SCENE, [tom], [TimedCommand(frame=0, command=cmds[0][1], sentence_id="s1")])
    eye, hips = stage.camera(60).eye, stage.tracks["Tom"].at(60)[0]
    assert float(np.linalg.norm((eye - hips)[[0, 2]])) < 2.7  # closer than the medium shot


def test_every_shot_with_one_of_eves_sentences_is_framed_from_where_she_is_seen(pair: list[Motion]) -> None:
    """A scorer that sees Eve only from the north (z < 0): each shot she acts in is framed from there."""

    class NorthForEve(Scorer):
        def shown(self, poses, frames, who) -> float:  # noqa: ANN001
            return float(self.shown_each(poses, frames, who).mean())

        def shown_each(self, poses, frames, who) -> np.ndarray:  # noqa: ANN001
            north = np.array([p.eye[2] < 0 for p in poses])
            return np.stack([north if w == "Eve" else np.ones(len(poses), bool) for w in who], axis=1)

    stage = Staging.build(SCENE, pair)
    shots = plan_shots(stage.motions, stage.tracks, [], stage.n_frames, ROOM, NorthForEve())
    keys = shot_keys(shots)
    for s, k in zip(shots, keys, strict=True):
        if "Eve" in s.acting:
            mid = (s.start + s.end) // 2
            assert camera_at(mid, keys, stage.tracks, ROOM).eye[2] < 0, (s, k)


def test_a_close_up_frames_the_character_who_acts_beside_its_subject() -> None:
    """Seen on the sheets: "camera close" before "They sit on the sofa and talk" held on Forrest's face
    for 1.5 s while Jenny sat down off-screen; "camera close on Professor Okafor" while Sam walked off rose
    to a top view that showed neither. Named or not, the close shot takes in whoever acts beside its
    subject, and stays the subject's."""
    from services.render.camera_checks import camera_checks

    tom = actor("Tom", 1.2, 0.0, 150, [("clap", 0, 150, "s2")])
    eve = actor("Eve", -1.2, -0.4, 150, [("wave", 0, 150, "s2")])
    implied = TimedCommand(
        frame=0,
        command=Command(kind="camera", value="close", target="Tom"),
        sentence_id="s1",
        implied_target=True,
    )
    stage = Staging.build(SCENE, [tom, eve], [implied])
    [close] = [s for s in stage.shots if s.source == "command"]
    assert (close.kind, close.subject, close.partner) == ("close", "Tom", "Eve")
    cmds = [("s1", Command(kind="camera", value="close"))]
    sentences = [("s1", "camera close"), ("s2", "Tom and Eve wave.")]
    checks = camera_checks(SCENE, [tom, eve], cmds, sentences, width=320, height=240)
    assert all(c.ok for c in checks["s2"] if c.name == "in_view"), checks["s2"]
    named = TimedCommand(
        frame=0, command=Command(kind="camera", value="close", target="Tom"), sentence_id="s1"
    )
    [held] = [s for s in Staging.build(SCENE, [tom, eve], [named]).shots if s.source == "command"]
    assert (held.subject, held.partner) == ("Tom", "Eve")
    alone = actor("Eve", -1.2, -0.4, 150, [])
    [held] = [s for s in Staging.build(SCENE, [tom, alone], [named]).shots if s.source == "command"]
    assert (held.subject, held.partner) == ("Tom", "")  # nobody else acts: Tom alone


class _AllSeen(Scorer):
    """A scorer that sees everyone from everywhere: only the faces can choose the side."""

    def shown(self, poses, frames, who) -> float:  # noqa: ANN001
        return 1.0

    def shown_each(self, poses, frames, who) -> np.ndarray:  # noqa: ANN001
        return np.ones((len(poses), len(who)), bool)


def test_two_people_side_by_side_are_filmed_from_the_front_not_from_behind() -> None:
    """Seen on a sheet: a talk on a sofa framed from behind its back, two backs of heads. Where every
    side shows them equally, the camera stands on the side their faces are."""
    eve = actor("Eve", -0.4, 0.0, 180, [("talk", 0, 90, "s1"), ("talk", 150, 180, "s3")])
    tom = actor("Tom", 0.4, 0.0, 180, [("talk", 90, 150, "s2")])  # both face +z, as on a sofa
    stage = Staging.build(SCENE, [eve, tom])
    assert stage.tracks["Eve"].facing[0][2] > 0.9
    shots = plan_shots(stage.motions, stage.tracks, [], stage.n_frames, ROOM, _AllSeen())
    keys = shot_keys(shots)
    for s in shots:
        if s.kind == "wide":
            continue
        mid = (s.start + s.end) // 2
        eye = camera_at(mid, keys, stage.tracks, ROOM).eye
        assert eye[2] > 0.3, (s, eye)  # in front of them


def test_an_unnamed_view_pairs_its_character_with_whoever_walks_farthest_away_in_the_sentence() -> None:
    """Seen in group-kitchen-09: under "camera left", "Sam drinks milk." and "Mom kisses Sam on the cheek
    and leaves." start together; the view paired Sam with Tom (farther from Sam when both began) and Mom
    walked out of the picture for 3 s. The pair is who is farthest apart over the sentence, not at its start."""
    from services.render.camera_checks import camera_checks

    bob = actor("Bob", -1.0, 0.0, 150, [("eat", 0, 150, "s1")])
    ann = actor("Ann", 0.0, 0.0, 150, [("drink", 0, 150, "s2")])
    cat = walk_motion("Cat", (0.4, 0.0), (2.6, -2.0), 150, expression="none")
    segs = [
        Segment(index=0, action="kiss_cheek", start_frame=0, end_frame=40, sentence_id="s3"),
        Segment(index=1, action="walk", start_frame=40, end_frame=150, sentence_id="s3"),
    ]
    cat = msgspec.structs.replace(cat, segments=segs)
    left = TimedCommand(
        frame=0,
        command=Command(kind="camera", value="left", target="Ann"),
        sentence_id="s0",
        implied_target=True,
    )
    stage = Staging.build(SCENE, [bob, ann, cat], [left])
    [view] = [s for s in stage.shots if s.source == "command"]
    assert (view.subject, view.partner) == ("Ann", "Cat")
    cmds = [("s0", Command(kind="camera", value="left"))]
    sentences = [("s0", "camera left"), ("s1", "Bob eats."), ("s2", "Ann drinks."), ("s3", "Cat leaves.")]
    checks = camera_checks(SCENE, [bob, ann, cat], cmds, sentences, width=320, height=240)
    for sid in ("s1", "s2", "s3"):
        assert all(c.ok for c in checks[sid] if c.name == "in_view"), checks[sid]


def test_a_sentence_split_over_shots_passes_by_what_all_of_them_miss():
    """A sentence's character is judged over the whole sentence, as the in_view check judges it: a shot
    holding its last fifth may leave a little of it unseen when the shots before showed the rest, and not
    when they already missed their share."""
    from services.render.director import Shot, _Unit, _unit_score

    unit = _Unit("Ada", np.arange(0, 100), key=3)
    shot = Shot(start=80, end=100, kind="medium", subject="Ada")
    frames = list(range(80, 100))
    shown = np.ones((20, 1))
    shown[:2, 0] = 0.0  # 2 of its 20 frames unseen: 90 % of this shot, 98 % of the sentence
    out: dict[int, float] = {}
    _, passes = _unit_score(shown, frames, ["Ada"], shot, [unit], {}, out)
    assert passes and out == {3: pytest.approx(2.0)}
    _, passes = _unit_score(shown, frames, ["Ada"], shot, [unit], {3: 4.0}, {})
    assert not passes  # 6 of 100 frames unseen: under 95 %
