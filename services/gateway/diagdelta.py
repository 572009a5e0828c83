"""Diagnostics as deltas: each live message carries only the sentences whose diagnostics or verdicts changed.

The channel keeps the diagnostics it last broadcast (`DiagnosticsState`, numbered by `seq`). A new state is
compared with it per sentence, with offsets relative to the sentence's start, so an edit earlier in the text
that only moves a sentence does not resend it. The message lists the sentences it replaces (`changed`, with
their entries at this version's offsets) and those that are gone (`dropped`); the editor shifts the entries
it keeps by how far their sentence moved. A client that does not hold the state a delta is based on
(`base_seq`) gets the whole state instead (`base_seq` null).

Every version gets two states: the pipeline's diagnostics (sent right after the animation, with the story
verdicts of the previous version kept for sentences that still exist: `verdicts_pending`), then the story
checks' W401 warnings and verdicts when they are ready (services.gateway.live runs them off the hot path).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

_SEQ = itertools.count(1)


def _relative(entry: dict[str, Any], origin: int) -> tuple[Any, ...]:
    """What makes two diagnostics of a sentence equal wherever the sentence is in the text."""
    return tuple((k, entry[k] - origin if k in ("start", "end") else entry[k]) for k in sorted(entry))


@dataclass(frozen=True)
class DiagnosticsState:
    """The diagnostics of one version as the editor sees them, per sentence."""

    version: int
    sentences: list[dict[str, Any]]
    unavailable: dict[str, str]
    entries: dict[str, list[dict[str, Any]]]  # sentence id -> its diagnostics (document offsets)
    verdicts: dict[str, dict[str, Any]]  # sentence id -> {"sentence_id", "verdict", "checks"}
    verdicts_pending: bool
    seq: int = field(default_factory=lambda: next(_SEQ))

    def starts(self) -> dict[str, int]:
        return {s["id"]: int(s["start"]) for s in self.sentences}

    def keys(self) -> dict[str, tuple[Any, ...]]:
        """Sentence id -> its diagnostics and verdict, independent of where the sentence is."""
        starts = self.starts()
        out: dict[str, tuple[Any, ...]] = {}
        for sid in set(self.entries) | set(self.verdicts) | set(starts):
            origin = starts.get(sid, 0)
            diags = tuple(_relative(e, origin) for e in self.entries.get(sid, []))
            verdict = self.verdicts.get(sid)
            out[sid] = (diags, repr(verdict) if verdict is not None else None)
        return out

    def carried_into(
        self,
        version: int,
        sentences: list[dict[str, Any]],
        unavailable: dict[str, str],
        entries: dict[str, list[dict[str, Any]]],
    ) -> DiagnosticsState:
        """A new version's pipeline diagnostics, with this state's verdicts (and their W401 warnings)
        kept, moved to the new offsets, for the sentences that still exist until the new ones are judged."""
        old_starts, new_starts = self.starts(), {s["id"]: int(s["start"]) for s in sentences}
        merged = {sid: list(items) for sid, items in entries.items()}
        kept: dict[str, dict[str, Any]] = {}
        for sid, verdict in self.verdicts.items():
            if sid not in new_starts or sid not in old_starts:
                continue
            kept[sid] = verdict
            shift = new_starts[sid] - old_starts[sid]
            for e in self.entries.get(sid, []):
                if "check" in e:
                    merged.setdefault(sid, []).append(
                        {**e, "start": e["start"] + shift, "end": e["end"] + shift}
                    )
        return DiagnosticsState(version, sentences, unavailable, merged, kept, verdicts_pending=True)

    def message(self, base: DiagnosticsState | None) -> dict[str, Any]:
        """The message that brings a client holding `base` (None: nothing) to this state."""
        if base is None:
            changed = sorted(set(self.entries) | set(self.verdicts) | set(self.starts()))
            dropped: list[str] = []
        else:
            mine, theirs = self.keys(), base.keys()
            changed = sorted(sid for sid, key in mine.items() if theirs.get(sid) != key)
            dropped = sorted(set(theirs) - set(mine))
        diags = [e for sid in changed for e in self.entries.get(sid, [])]
        diags.sort(key=lambda d: (d["start"], d["end"], d["code"]))
        return {
            "type": "diagnostics",
            "version": self.version,
            "seq": self.seq,
            "base_seq": None if base is None else base.seq,
            "sentences": self.sentences,
            "unavailable": self.unavailable,
            "changed": changed,
            "dropped": dropped,
            "diagnostics": diags,
            "verdicts": [self.verdicts[sid] for sid in changed if sid in self.verdicts],
            "verdicts_pending": self.verdicts_pending,
        }
