import numpy as np

from proto.motion_data import Motion, Segment
from services.orchestrator.timeline import Beat, assemble, schedule
from wana.arrays import from_wire, to_wire
from wana.domain.skeleton import N_JOINTS


def test_a_characters_actions_follow_one_another():
    starts = schedule([Beat("s1", "Eve", 0, 30), Beat("s1", "Eve", 1, 20), Beat("s2", "Eve", 2, 10)])
    assert starts == {("Eve", 0): 0, ("Eve", 1): 30, ("Eve", 2): 50}


def test_a_later_sentence_never_starts_before_the_one_before_it():
    beats = [Beat("s1", "Eve", 0, 90), Beat("s2", "Eve", 1, 60), Beat("s3", "Tom", 0, 40)]
    starts = schedule(beats)
    # Tom's sentence comes after Eve's second one, which starts at 90: Tom waits for it, then overlaps it.
    assert starts[("Tom", 0)] == 90


def test_characters_in_one_sentence_start_together():
    starts = schedule([Beat("s1", "Eve", 0, 50), Beat("s2", "Eve", 1, 10), Beat("s2", "Tom", 0, 10)])
    assert starts[("Eve", 1)] == starts[("Tom", 0)] == 50


def test_a_response_starts_after_the_action_it_answers_plus_its_delay():
    beats = [Beat("s1", "Tom", 0, 90), Beat("s2", "Mary", 0, 40), Beat("s3", "Eve", 0, 10)]
    starts = schedule(beats, responses={("Mary", 0): (("Tom", 0), 0.5)})
    assert starts[("Mary", 0)] == 90 + 15
    assert starts[("Eve", 0)] == 105  # later sentences still follow the story order
    # without the response, Mary would have started with Tom's sentence
    assert schedule(beats)[("Mary", 0)] == 0


def test_a_response_to_an_action_later_in_the_text_is_ignored():
    beats = [Beat("s1", "Mary", 0, 40), Beat("s2", "Tom", 0, 90)]
    starts = schedule(beats, responses={("Mary", 0): (("Tom", 0), 0.5)})
    assert starts == {("Mary", 0): 0, ("Tom", 0): 0}


def test_a_wait_holds_later_sentences_until_everything_earlier_is_over():
    beats = [Beat("s1", "Eve", 0, 30), Beat("s3", "Tom", 0, 10)]
    starts = schedule(beats, {"s2": 2.0}, ["s1", "s2", "s3"])
    assert starts[("Tom", 0)] == 30 + 60


def piece(frames: int, x: float, action: str) -> Motion:
    root = np.zeros((frames, 3), np.float32)
    root[:, 0] = x
    rot = np.zeros((frames, N_JOINTS, 4), np.float32)
    rot[..., 3] = 1
    return Motion(
        character="Eve",
        root_position=to_wire(root),
        rotations=to_wire(rot),
        segments=[Segment(index=0, action=action, start_frame=0, end_frame=frames, sentence_id="s")],
    )


def test_assembly_holds_the_pose_through_gaps_and_shifts_segments():
    motion = assemble("Eve", [piece(10, 1.0, "walk"), piece(5, 2.0, "wave")], [4, 20], total=30)
    root = from_wire(motion.root_position)
    assert root.shape == (30, 3)
    assert np.all(root[:4, 0] == 1.0)  # before the first action: its first pose
    assert np.all(root[14:20, 0] == 1.0)  # between actions: the last pose held
    assert np.all(root[20:25, 0] == 2.0) and np.all(root[25:, 0] == 2.0)
    spans = [(s.action, s.start_frame, s.end_frame) for s in motion.segments]
    assert spans == [("hold", 0, 4), ("walk", 4, 14), ("hold", 14, 20), ("wave", 20, 25), ("hold", 25, 30)]
