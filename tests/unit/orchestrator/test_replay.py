"""Where a story pass resumes and where it stops (services/orchestrator/stages/replay.py)."""

from __future__ import annotations

from proto.motion import SegmentEndState
from services.orchestrator.stages.replay import Carried, Outputs, PassTrace, resume_at, same_from


def carried(x: float) -> Carried:
    return Carried({"Eve": SegmentEndState(x=x, z=0.0, yaw=0.0)}, set(), {("sofa", "0"): "Eve"}, {}, {})


def trace(keys: list[str], context: str = "room") -> PassTrace:
    after = [carried(float(i)) for i in range(len(keys))]
    counts = [({"Eve": i + 1}, 0, 0) for i in range(len(keys))]
    return PassTrace(context, keys, after, [c.digest() for c in after], counts, Outputs({"Eve": []}))


def test_a_pass_resumes_after_the_steps_it_shares_with_the_last_one():
    last = trace(["a", "b", "c", "d"])
    assert resume_at(last, "room", ["a", "b", "X", "d"]) == 2
    assert resume_at(last, "room", ["a", "b", "c", "d", "e"]) == 4
    assert resume_at(last, "room", ["X", "b", "c", "d"]) == 0


def test_a_pass_in_another_context_or_without_a_trace_walks_from_the_start():
    assert resume_at(trace(["a", "b"]), "another room", ["a", "b"]) == 0
    assert resume_at(None, "room", ["a", "b"]) == 0


def test_the_unchanged_tail_starts_after_the_last_changed_step():
    last = trace(["a", "b", "c", "d"])
    assert same_from(last, "room", ["a", "X", "c", "d"]) == 2
    assert same_from(last, "room", ["a", "b", "c", "X"]) == 4  # nothing after the last step
    assert same_from(last, "room", ["a", "b", "c"]) == 4  # steps shifted: never compared
    assert same_from(last, "another room", ["a", "b", "c", "d"]) == 5


def test_the_carried_state_digest_tells_states_and_slot_order_apart():
    assert carried(1.0).digest() == carried(1.0).digest()
    assert carried(1.0).digest() != carried(2.0).digest()
    one, two = carried(1.0), carried(1.0)
    one.held[("chair", "0")] = "Tom"
    two.held = {("chair", "0"): "Tom", ("sofa", "0"): "Eve"}  # same slots, taken in another order
    assert one.digest() != two.digest()


def test_a_copy_of_the_carried_state_does_not_follow_the_live_one():
    live = carried(1.0)
    saved = live.copy()
    live.states["Eve"] = SegmentEndState(x=5.0, z=0.0, yaw=0.0)
    live.held.clear()
    live.outside.add("Tom")
    assert saved.digest() == carried(1.0).digest()


def test_outputs_are_cut_to_a_step_and_extended_with_the_rest_of_the_last_pass():
    last = Outputs({"Eve": ["m0", "m1", "m2"]}, [("s1", "note")], [])  # type: ignore[list-item]
    cut = last.upto(({"Eve": 1}, 0, 0))
    assert cut.pieces == {"Eve": ["m0"]} and cut.notes == []
    cut.pieces["Eve"].append("m1'")  # type: ignore[arg-type]
    cut.extended(last, ({"Eve": 2}, 0, 0))
    assert cut.pieces == {"Eve": ["m0", "m1'", "m2"]} and cut.notes == [("s1", "note")]
    assert last.pieces == {"Eve": ["m0", "m1", "m2"]}  # the last pass's outputs are not touched
