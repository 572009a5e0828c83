"""Checkpoints of a pass over the story (`segments`): an edit replays only the actions it reaches.

A pass walks every action in story order and carries a state from one to the next (where each character
stands, who is off stage, which slots are held, the lanes left at the door, the last walks). Each action's
node is memoised, but the walk itself (views, slot claims, input hashes) costs as much as the story is long.
A `PassTrace` keeps, of the last pass that finished, each step's key (what the step reads besides the
carried state), the carried state after it and what it added to the pass's outputs. The next pass then

- starts after the longest run of leading steps whose keys are unchanged, from the state saved there (the
  actions before an edit are not walked again), and
- stops as soon as, after a step it ran, the carried state is the one the last pass had there and every
  later step's key is unchanged (early cutoff): the rest of the outputs are the last pass's.

The steps skipped either way are logged as reused, as their nodes would be, so the query log is the one a
full walk writes. Only a pass that finished leaves a trace (one that failed part-way leaves none).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from proto.motion import PairedAction, SegmentEndState
from proto.motion_data import Motion
from services.orchestrator.queries import content_hash

Trail = tuple[int, list[tuple[float, float]]]


@dataclass
class Carried:
    """What one step of a pass hands the next."""

    states: dict[str, SegmentEndState]
    outside: set[str]
    held: dict[tuple[str, str], str]  # the slot book (Slotting.book.held), in its insertion order
    exit_lanes: dict[str, list[tuple[float, float]]]
    trails: dict[str, Trail]

    def copy(self) -> Carried:
        return Carried(
            dict(self.states),
            set(self.outside),
            dict(self.held),
            {sid: list(lanes) for sid, lanes in self.exit_lanes.items()},
            dict(self.trails),
        )

    def digest(self) -> str:
        return content_hash(
            [
                sorted(self.states.items()),
                sorted(self.outside),
                [[*key, who] for key, who in self.held.items()],
                sorted(self.exit_lanes.items()),
                sorted(self.trails.items()),
            ]
        )


@dataclass
class Outputs:
    """What a pass returns and collects: each character's pieces, the notes, the hand-overs."""

    pieces: dict[str, list[Motion]]
    notes: list[tuple[str, str]] = field(default_factory=list)
    handovers: list[PairedAction] = field(default_factory=list)

    def counts(self) -> tuple[dict[str, int], int, int]:
        return {n: len(p) for n, p in self.pieces.items()}, len(self.notes), len(self.handovers)

    def upto(self, counts: tuple[dict[str, int], int, int]) -> Outputs:
        """A copy of the first ``counts`` of each output (the outputs as they were after that step)."""
        pieces, notes, handovers = counts
        return Outputs(
            {n: list(p[: pieces[n]]) for n, p in self.pieces.items()},
            list(self.notes[:notes]),
            list(self.handovers[:handovers]),
        )

    def extended(self, last: Outputs, counts: tuple[dict[str, int], int, int]) -> None:
        """Append what ``last`` added after ``counts`` (the rest of an unchanged pass)."""
        pieces, notes, handovers = counts
        for n, p in last.pieces.items():
            self.pieces[n].extend(p[pieces[n] :])
        self.notes.extend(last.notes[notes:])
        self.handovers.extend(last.handovers[handovers:])


@dataclass
class PassTrace:
    """One finished pass: its context's hash, each step's key, and after each step the carried state (with
    its digest) and the outputs' counts; the outputs at the end."""

    context: str
    keys: list[str]
    after: list[Carried]
    digests: list[str]
    counts: list[tuple[dict[str, int], int, int]]
    outputs: Outputs


def resume_at(trace: PassTrace | None, context: str, keys: list[str]) -> int:
    """How many leading steps the last pass shares with this one (0: walk from the start)."""
    if trace is None or trace.context != context:
        return 0
    n = 0
    for mine, theirs in zip(keys, trace.keys, strict=False):
        if mine != theirs:
            break
        n += 1
    return n


def same_from(trace: PassTrace | None, context: str, keys: list[str]) -> int:
    """The first step from which every key is the last pass's (steps aligned one to one: same context and
    as many steps); one past the end when the passes cannot be compared. After a step ``i`` with
    ``i + 1 >= same_from`` whose carried state is the last pass's there, the rest of the pass is the last's."""
    if trace is None or trace.context != context or len(trace.keys) != len(keys):
        return len(keys) + 1
    m = len(keys)
    while m > 0 and keys[m - 1] == trace.keys[m - 1]:
        m -= 1
    return m


def step_key(*parts: Any) -> str:
    """A step's key: the hash of what it reads besides the carried state."""
    return content_hash(list(parts))
