"""The render side's story checks: in_view (the acting character in the picture and unhidden) and
command_visible (a camera or light command in force long enough to be seen).

Scenes are built so that the answer is known from geometry: a wardrobe between a fixed camera and Eve, the
same camera moved to her side, a camera outside the room (its walls are one-sided) or inside it with Eve
outside, Tom standing in the line of sight, and the commanded close-up of Tom while Eve acts 3 m away.
"""

from __future__ import annotations

import msgspec
import numpy as np
import pytest

from proto.motion_data import Segment
from proto.render import TimedCommand
from proto.scene import PlacedObject, Room, Scene
from proto.ssg import Command
from services.render.camera_checks import camera_checks, command_checks, staged_checks
from services.render.demo import demo_scene, walk_motion
from services.render.framing import segments_hit_boxes
from services.render.renderer import FrameRenderer
from services.render.sightlines import Furniture, box_triangles, segments_hit_triangles
from services.render.staging import CameraTrack, Staging, camera_track
from services.render.timeline import COMMAND_HOLD_FRAMES, n_frames_of, place_commands, video_frames
from services.render.visibility import BODY_POINTS, body_view
from wana.domain.skeleton import JOINT_INDEX

N = 60
ROOM = Room(room_type="bedroom", width=6.0, depth=5.0, height=2.8)
WARDROBE = PlacedObject(id="wardrobe", category="wardrobe", position=(0.0, 0.0, 0.8), yaw=0.0)  # z 0.49..1.11


def standing(name: str, x: float, z: float, sentence_id: str = "s1"):  # noqa: ANN201
    """A character walking on the spot at (x, z) for N frames, serving sentence s1."""
    return walk_motion(name, (x, z), (x, z), N, sentence_id=sentence_id)


def fixed_camera(
    eye: tuple[float, float, float], target: tuple[float, float, float], n: int = N
) -> CameraTrack:
    return CameraTrack(
        eye=np.tile(np.asarray(eye, float), (n, 1)),
        target=np.tile(np.asarray(target, float), (n, 1)),
        up=np.tile([0.0, 1.0, 0.0], (n, 1)),
        fov_deg=np.full(n, 55.0),
    )


def in_view(scene: Scene, motions, track: CameraTrack, who: str = "Eve"):  # noqa: ANN001, ANN201
    stage = Staging.build(scene, motions)
    checks = staged_checks(stage, [("s1", "Eve waves at Tom.")], width=320, height=240, track=track)
    return next(c for c in checks["s1"] if c.name == "in_view" and c.character == who)


def test_a_character_behind_a_wardrobe_is_not_in_view_and_the_reason_names_the_wardrobe():
    scene = Scene(room=ROOM, objects=[WARDROBE])
    check = in_view(scene, [standing("Eve", 0.0, 0.0)], fixed_camera((0.0, 1.3, 2.4), (0.0, 1.0, 0.0)))
    assert not check.ok
    assert "hidden behind the wardrobe" in check.reason and "'Eve waves at Tom'" in check.reason
    assert check.frames == list(range(N)) and check.character == "Eve"


def test_the_same_character_seen_from_the_side_is_in_view():
    scene = Scene(room=ROOM, objects=[WARDROBE])
    check = in_view(scene, [standing("Eve", 0.0, 0.0)], fixed_camera((2.4, 1.3, 0.0), (0.0, 1.0, 0.0)))
    assert check.ok, check.reason
    assert "in view" in check.reason


def test_a_camera_looking_away_puts_the_character_out_of_frame():
    scene = Scene(room=ROOM, objects=[])
    check = in_view(scene, [standing("Eve", 0.0, 0.0)], fixed_camera((0.0, 1.3, 2.4), (0.0, 1.0, 5.0)))
    assert not check.ok and "Eve is out of frame for 2.0 s of 'Eve waves at Tom'" in check.reason
    assert check.essential


def test_walls_hide_only_what_is_outside_the_room_seen_from_inside():
    scene = Scene(room=ROOM, objects=[])
    inside = standing("Eve", 0.0, 0.0)
    from_outside = in_view(scene, [inside], fixed_camera((0.0, 1.5, 4.0), (0.0, 1.0, 0.0)))
    assert from_outside.ok, "walls are one-sided: a camera outside the room sees into it"
    outside = standing("Eve", 0.0, 3.2)  # beyond the front wall at z = 2.5
    from_inside = in_view(scene, [outside], fixed_camera((0.0, 1.5, 0.0), (0.0, 1.0, 3.2)))
    assert not from_inside.ok and "behind the wall" in from_inside.reason


def test_another_character_in_the_line_of_sight_hides_the_actor():
    scene = Scene(room=ROOM, objects=[])
    eve, tom = standing("Eve", 0.0, 0.0), standing("Tom", 0.0, 1.0, sentence_id="")
    check = in_view(scene, [eve, tom], fixed_camera((0.0, 1.1, 2.4), (0.0, 1.0, 0.0)))
    assert not check.ok and "hidden behind Tom" in check.reason
    side = in_view(scene, [eve, tom], fixed_camera((2.4, 1.1, 0.0), (0.0, 1.0, 0.0)))
    assert side.ok, side.reason


def test_a_body_part_sunk_into_furniture_is_not_hidden_by_it_but_one_behind_it_is():
    """Feet inside a low crate are the penetration check's finding (no camera could show them); a crate in
    front of the feet hides them, and so does a far wall of the very crate they are in."""
    stage = Staging.build(Scene(room=ROOM, objects=[]), [standing("Eve", 0.0, 0.0)])
    joints = {n: r.joint_positions for n, r in stage.rigs.items()}
    feet = [BODY_POINTS.index("LeftFoot"), BODY_POINTS.index("RightFoot")]

    def feet_hidden(box: list[list[float]], eye: tuple[float, float, float]) -> np.ndarray:
        crate = Furniture.from_boxes([np.array([box])], ["crate"])
        view = body_view(
            "Eve", np.arange(N), joints, fixed_camera(eye, (0.0, 0.2, 0.0)), crate, ROOM, 320, 240
        )
        assert view.in_frame[:, feet].all()
        return view.hidden_by[:, feet] >= 0

    from_above, low = (0.0, 2.6, 1.0), (0.0, 0.3, 2.4)
    assert not feet_hidden([[-0.5, 0.0, -0.45], [0.5, 0.2, 0.45]], from_above).any()  # sunk in its top
    assert feet_hidden([[-0.5, 0.0, 0.6], [0.5, 0.45, 0.9]], low).all()  # a crate in front of them
    assert feet_hidden([[-0.5, 0.0, -0.45], [0.5, 0.45, 1.5]], low).all()  # entered 1 m before the feet


def test_a_commanded_close_up_of_tom_keeps_eve_acting_elsewhere_in_view_end_to_end():
    """The measured close-up of Tom is played from its first frame (no ease from the overview that lost
    Eve for 0.4 s), turned until Eve, who acts, is in the picture too; a close-up that frames Tom
    alone loses her, and the check says so."""
    eve = standing("Eve", -2.0, 0.0)
    tom = standing("Tom", 2.0, -1.0, sentence_id="")
    sentences = [("s0", "camera close"), ("s1", "Eve waves at Tom.")]
    commands = [("s0", Command(kind="camera", value="close", target="Tom"))]
    checks = camera_checks(demo_scene(), [eve, tom], commands, sentences, width=320, height=240)
    eve_check = next(c for c in checks["s1"] if c.name == "in_view")
    assert eve_check.ok, eve_check.reason
    stage = Staging.build(demo_scene(), [eve, tom], place_commands(commands, sentences, [eve, tom]))
    [close] = [s for s in stage.shots if s.source == "command"]
    assert (close.kind, close.subject, close.start) == ("close", "Tom", 0)
    tom_only = fixed_camera((3.2, 1.3, -0.2), (2.0, 1.0, -1.0))  # in front of Tom, Eve behind the lens
    lost = staged_checks(stage, sentences[1:], width=320, height=240, track=tom_only)["s1"]
    lost_eve = next(c for c in lost if c.name == "in_view")
    assert not lost_eve.ok and "Eve is out of frame" in lost_eve.reason


def test_the_camera_track_is_the_camera_the_video_uses():
    eve = walk_motion("Eve", (-2.0, 1.0), (1.0, -1.0), 90, sentence_id="s1")
    sentences = [("s1", "Eve walks."), ("s2", "camera left")]
    commands = [("s2", Command(kind="camera", value="left"))]
    track = camera_track(demo_scene(), [eve], commands, sentences, width=320, height=240)
    renderer = FrameRenderer(
        demo_scene(), [eve], place_commands(commands, sentences, [eve]), width=320, height=240
    )
    assert len(track) == renderer.n_frames == 90 + COMMAND_HOLD_FRAMES
    for f in (0, 30, 89, 100, len(track) - 1):
        pose = renderer.camera(f)
        np.testing.assert_allclose(track.eye[f], pose.eye)
        np.testing.assert_allclose(track.target[f], pose.target)
        assert track.fov_deg[f] == pose.fov_deg


def _story_ending_in_a_command():  # noqa: ANN202
    eve = walk_motion("Eve", (-1.0, 0.0), (1.0, 0.0), N, sentence_id="s1")
    sentences = [("s1", "Eve walks."), ("s2", "camera close")]
    timed = place_commands([("s2", Command(kind="camera", value="close"))], sentences, [eve])
    return eve, sentences, timed


def test_a_command_on_the_last_frame_fails_without_the_hold_and_passes_with_it():
    eve, sentences, timed = _story_ending_in_a_command()
    assert timed[0].frame == N and timed[0].sentence_id == "s2"
    unheld = command_checks(timed, n_frames_of([eve]))["s2"][0]  # the video as long as the motion
    assert not unheld.ok and unheld.essential
    assert unheld.reason.startswith("camera close takes effect 0.0 s before the end of the video")
    assert video_frames([eve], timed) == N + COMMAND_HOLD_FRAMES
    held = camera_checks(demo_scene(), [eve], [("s2", Command(kind="camera", value="close"))], sentences)
    check = held["s2"][0]
    assert check.ok and check.name == "command_visible", check.reason
    assert check.frames == list(range(N, N + COMMAND_HOLD_FRAMES))


def test_a_command_replaced_too_soon_fails_and_different_kinds_do_not_replace_each_other():
    cmd = {v: Command(kind="camera", value=v) for v in ("left", "top")}
    timed = [
        TimedCommand(frame=0, command=cmd["left"], sentence_id="a"),
        TimedCommand(frame=0, command=Command(kind="weather", value="night"), sentence_id="b"),
        TimedCommand(frame=20, command=cmd["top"], sentence_id="c"),
    ]
    checks = command_checks(timed, 200)
    assert not checks["a"][0].ok and "before camera top replaces it" in checks["a"][0].reason
    assert checks["b"][0].ok and checks["c"][0].ok


def test_the_held_video_repeats_the_final_pose():
    eve, _, timed = _story_ending_in_a_command()
    stage = Staging.build(demo_scene(), [eve], timed)
    rig = stage.rigs["Eve"]
    last, held = rig.vertices([N - 1])[0], rig.vertices([stage.n_frames - 1])[0]
    np.testing.assert_array_equal(last, held)


def test_export_reply_carries_checks_and_reads_back_with_plain_msgpack():
    import msgpack

    from proto.common import Header
    from proto.render import ExportReply

    check = command_checks(_story_ending_in_a_command()[2], N)["s2"][0]
    reply = ExportReply(
        header=Header(),
        format="mp4",
        filename="a.mp4",
        media_type="video/mp4",
        data=b"",
        checks={"s2": [check]},
    )
    plain = msgpack.unpackb(msgspec.msgpack.encode(reply))
    assert plain["checks"]["s2"][0]["name"] == "command_visible" and plain["checks"]["s2"][0]["ok"] is False
    old = msgspec.msgpack.decode(
        msgspec.msgpack.encode({k: v for k, v in plain.items() if k != "checks"}), type=ExportReply
    )
    assert old.checks == {}


@pytest.mark.slow
def test_write_outputs_returns_the_checks_and_reports_them(tmp_path):
    import json

    from services.render.export import write_outputs

    eve, sentences, _ = _story_ending_in_a_command()
    paths = write_outputs(
        tmp_path,
        demo_scene(),
        [eve],
        [("s2", Command(kind="camera", value="close"))],
        sentences,
        {},
        width=96,
        height=64,
        progress=False,
    )
    assert sorted(paths.checks) == ["s1", "s2"]
    assert paths.checks["s2"][0].ok
    report = json.loads(paths["report.json"].read_text())
    assert report["render"]["checks"]["s2"][0]["name"] == "command_visible"
    assert report["render"]["frames"] == N + COMMAND_HOLD_FRAMES


def test_segments_without_a_sentence_get_no_check():
    eve = msgspec.structs.replace(
        standing("Eve", 0.0, 0.0), segments=[Segment(index=0, action="hold", start_frame=0, end_frame=N)]
    )
    assert camera_checks(demo_scene(), [eve], [], []) == {}


def test_triangle_sight_lines_agree_with_the_slab_test_on_boxes():
    rng = np.random.default_rng(7)
    boxes = np.sort(rng.uniform(-1, 1, (6, 2, 3)), axis=1)
    starts, ends = rng.uniform(-2, 2, (400, 3)), rng.uniform(-2, 2, (400, 3))
    by_slab = segments_hit_boxes(starts, ends, boxes).any(axis=1)
    by_triangles = segments_hit_triangles(starts, ends, box_triangles(boxes))
    assert 50 < by_slab.sum() < 350  # both outcomes occur
    # A segment that starts or ends inside a box crosses no face; the slab test counts it, triangles do not.
    inside = np.zeros(len(starts), dtype=bool)
    for b in boxes:
        inside |= np.all((starts >= b[0]) & (starts <= b[1]), axis=1) | np.all(
            (ends >= b[0]) & (ends <= b[1]), axis=1
        )
    assert (by_slab[~inside] == by_triangles[~inside]).all()


def test_sight_lines_beside_a_desk_leg_are_clear_though_they_cross_its_voxels():
    """The voxels are a superset of the drawn desk: a line past a 4 cm leg crosses the leg's 11 cm voxel."""
    desk = PlacedObject(id="desk", category="desk", position=(0.0, 0.0, 0.0), yaw=0.0)
    furniture = Furniture.from_scene(Scene(room=ROOM, objects=[desk]))
    starts = np.array([[x, 0.45, -1.0] for x in np.linspace(-0.7, 0.7, 57)])  # knee height, front to back
    ends = starts + [0.0, 0.0, 2.0]
    by_voxels = segments_hit_boxes(starts, ends, furniture.boxes[0]).any(axis=1)
    by_mesh = furniture.first_blocker(starts, ends) == 0
    assert not (by_mesh & ~by_voxels).any()  # the voxels are conservative
    assert (by_voxels & ~by_mesh).sum() >= 4  # beside the legs: clear in the picture
    assert by_mesh.any() and not by_mesh.all()


def test_the_tally_counts_each_in_view_checks_frames_in_the_picture_and_hidden():
    from services.render.camera_checks import ViewTally

    scene = Scene(room=ROOM, objects=[WARDROBE])
    stage = Staging.build(scene, [standing("Eve", 0.0, 0.0)])
    behind = fixed_camera((0.0, 1.3, 2.4), (0.0, 1.0, 0.0))  # the wardrobe between lens and Eve
    away = fixed_camera((0.0, 1.3, 2.4), (3.0, 1.0, 2.4))  # looking along the wall, Eve out of the picture
    for track, want in ((behind, (N, N, N)), (away, (N, 0, 0))):
        tally: list[ViewTally] = []
        staged_checks(stage, [("s1", "Eve waves.")], width=320, height=240, track=track, tally=tally)
        assert [(t.sentence_id, t.character) for t in tally] == [("s1", "Eve")]
        assert (tally[0].frames, tally[0].in_frame, tally[0].occluded) == want


def test_camera_close_is_judged_by_the_picture_not_by_the_plan():
    """duo-kitchen-03 s8 (fresh label): "camera close" passed on the plan's 1.5 s while Anna stayed
    full-figure on every frame; the same command through a camera a metre from Tom's face passes."""
    tom = standing("Tom", 2.0, -1.0, sentence_id="s1")
    sentences = [("s0", "camera close"), ("s1", "Tom waves.")]
    commands = [("s0", Command(kind="camera", value="close", target="Tom"))]
    stage = Staging.build(demo_scene(), [tom], place_commands(commands, sentences, [tom]))
    head = stage.rigs["Tom"].joint_positions[0, JOINT_INDEX["Head"]]
    chest = (2.0, float(head[1]) - 0.15, -1.0)  # the camera aims between his head and chest

    def close_check(eye):  # noqa: ANN001, ANN202
        track = fixed_camera(eye, chest, n=stage.n_frames)
        checks = staged_checks(stage, sentences, width=320, height=240, track=track)["s0"]
        return next(c for c in checks if c.name == "command_visible")

    far = close_check((2.0, 1.5, 4.0))  # 5 m off: the whole room, Tom full-figure
    assert not far.ok and "never comes close" in far.reason, far.reason
    near = close_check((2.0, float(head[1]), 0.0))  # 1 m in front of him
    near_back = close_check((2.0, float(head[1]), -2.0))  # or behind: a head and shoulders either way
    assert near.ok and near_back.ok, (near.reason, near_back.reason)


def test_a_close_shot_from_straight_above_is_close():
    """gump-living_room-3 s9 (fresh3): a close shot looking down on the two on the sofa filled the picture,
    but the head-to-chest line, seen end on from above, spanned 12 % of the frame's height: 'never close'."""
    tom = standing("Tom", 2.0, -1.0, sentence_id="s1")
    sentences = [("s0", "camera close"), ("s1", "Tom waves.")]
    commands = [("s0", Command(kind="camera", value="close", target="Tom"))]
    stage = Staging.build(demo_scene(), [tom], place_commands(commands, sentences, [tom]))
    head = stage.rigs["Tom"].joint_positions[0, JOINT_INDEX["Head"]]

    def from_above(height: float):  # noqa: ANN202
        track = fixed_camera((2.0, float(head[1]) + height, -0.98), (2.0, 0.0, -1.0), n=stage.n_frames)
        checks = staged_checks(stage, sentences, width=320, height=240, track=track)["s0"]
        return next(c for c in checks if c.name == "command_visible")

    near = from_above(1.0)  # a metre over his head
    assert near.ok, near.reason
    high = from_above(4.5)  # under the ceiling of a tall hall: the whole room from above
    assert not high.ok and "never comes close" in high.reason, high.reason


def test_the_writers_camera_close_is_close_in_the_picture_the_director_draws():
    """solo-office-01 s7: "camera close" on a typist drew the director's head-to-knees close-up (head to chest
    at most 25 % of the frame, under 22 % on all but 0.5 s); the command's own framing comes closer."""
    tom = standing("Tom", 2.0, -1.0, sentence_id="s1")
    sentences = [("s0", "camera close"), ("s1", "Tom waves.")]
    commands = [("s0", Command(kind="camera", value="close", target="Tom"))]
    stage = Staging.build(demo_scene(), [tom], place_commands(commands, sentences, [tom]))
    checks = staged_checks(stage, sentences, width=320, height=240)
    close = next(c for c in checks["s0"] if c.name == "command_visible")
    assert close.ok and "fill" in close.reason, close.reason
    span = float(close.reason.rsplit("fill ", 1)[1].split("%")[0]) / 100.0
    assert span >= 0.3, close.reason
    assert all(c.ok for c in checks["s1"] if c.name == "in_view"), checks["s1"]


def test_a_window_on_the_wall_behind_the_camera_hides_nobody():
    """The wall the camera stands behind is cut away with what hangs on it (the renderer does not draw the
    window there), so the window does not hide Eve; from inside the room the same window does."""
    window = PlacedObject(id="window", category="window", position=(0.0, 0.9, 2.47), yaw=np.pi)  # front wall
    scene = Scene(room=ROOM, objects=[window])
    through = in_view(scene, [standing("Eve", 0.0, 0.0)], fixed_camera((0.0, 1.4, 4.0), (0.0, 1.0, 0.0)))
    assert through.ok, through.reason
    outside = standing("Eve", 0.0, 3.2)
    from_inside = in_view(scene, [outside], fixed_camera((0.0, 1.4, 0.5), (0.0, 1.2, 3.2)))
    assert not from_inside.ok
