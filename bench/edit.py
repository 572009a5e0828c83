#!/usr/bin/env python
"""Edit-to-animation latency through the gateway's WebSocket, incremental against full recompute.

A real gateway (uvicorn on a free loopback port, in this process) over a fresh SQLite file; a real
WebSocket client. For a 20-sentence document it measures the time from sending an edit message to
receiving the `animation` message of the version that edit produced:

- action edit: one word of one action sentence changes (walks <-> runs, rotating over the sentences);
- scene edit: one word of one scene sentence changes (window <-> door);
- late action edit: Tom's last walk (walks <-> runs), which leaves Eve's body motion as it was, so the
  gateway sends her as an `unchanged` stub and the message carries one character's arrays;
- full: a new document holding the whole text, from opening its WebSocket to its first animation
  message (cold: nothing memoised for it; the services' models are warmed up on another document first).

ratio = action_edit_p50_ms / full_ms. Targets (issue 9): action edit p50 <= 150 ms, ratio <= 0.1.

    .venv/bin/python bench/edit.py --quick --json bench/results/edit.json

Writes {"action_edit_p50_ms", "scene_edit_p50_ms", "full_ms", "ratio"} (stable keys), plus
"gateway_share_p50_ms" (latency not spent in Session.compute), "animation_message_kib_p50" and
"unchanged_character_share" (characters the gateway sent as `unchanged` stubs), "late_action_edit_p50_ms"
and "late_action_animation_kib_p50", and "bytes_per_action_edit_p50": every byte the WebSocket received from
sending a one-word action edit to its story verdicts (the animation, then the diagnostics deltas), in a
3-character document (issue 20: <= 50 kB); p95 is in the table, and "bytes_per_action_edit_by_type_p50"
splits it by message type (animation, diagnostics, progress, ack). Animation messages are read as binary
frames, as the editor reads them (and large JSON messages as the WJZ1 frames they come as: their
compressed bytes count). The verdicts follow the animation off the hot path:
"verdicts_after_animation_p50_ms" is how long after it they arrive, "diagnostics_bytes_per_edit_p50" their
bytes; each edit waits for them before the next is sent.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from services.gateway import animwire  # noqa: E402  (after the repository is on the path)

SEED = 0  # the pipeline's seed: the same edits give the same animations

SCENE = [
    "In the office there is a desk near a window$.",
    "A laptop is on the desk$.",
    "A chair is in front of the desk$.",
    "A sofa is next to the bookshelf$.",
    "A lamp is on the side table$.",
]
ACTIONS = [
    "Eve walks to the chair.",
    "Eve sits on the chair.",
    "Eve types on the laptop.",
    "camera left",
    "Tom walks to the sofa.",
    "Tom waves at Eve.",
    "They are colleagues.",
    "Tom sits on the sofa.",
    "Eve stands up.",
    "Eve walks to the window.",
    "Tom walks to the lamp.",
    "Eve waves at Tom.",
    "Tom walks to the desk.",
    "night",
    "Eve walks to the sofa.",
]
# bytes per action edit (issue 20): three characters whose sentences interleave, so every edit moves the
# later frames of all three in time
THREE = [
    "Eve walks to the chair.",
    "Eve sits on the chair.",
    "Tom walks to the sofa.",
    "Tom waves at Eve.",
    "Ann walks to the lamp.",
    "Tom sits on the sofa.",
    "Ann walks to the window.",
    "Eve stands up.",
    "Eve walks to the window.",
    "Ann walks to the desk.",
    "Tom stands up.",
    "Tom walks to the lamp.",
]
WARM_UP = "In the kitchen there is a table$. A cup is on the table$. Ann walks to the table. Ann drinks."


def document() -> str:
    """The 20-sentence benchmark document (5 scene sentences, 13 action sentences, 2 commands)."""
    lines = [" ".join(SCENE)] + ACTIONS
    text = "\n".join(lines)
    assert len(SCENE) + len(ACTIONS) == 20
    return text


def three_character_document() -> str:
    """The 3-character document of the bytes-per-edit measure (the scene of `document`, 12 actions)."""
    return "\n".join([" ".join(SCENE), *THREE])


class LiveClient:
    """A WebSocket client of one document that tracks the text and version.

    It reads animation messages as the editor does (binary frames, `?wire=binary`) and rebuilds every
    patched character from the one it holds, checking that it was sent everything it needs.
    """

    def __init__(self, ws_base: str, doc_id: str) -> None:
        from websockets.sync.client import connect

        self.held: dict[str, Any] = {}  # character hash -> its frames (animwire.Quantised)
        self.received_bytes = 0  # bytes of every message received so far
        self.bytes_by_type: dict[str, int] = {}  # the same, by message type
        self.overheads: list[float] = []  # ms of each edit's latency not spent in Session.compute
        self.animation_kb: list[float] = []  # size of each edit's animation message
        self.unchanged: list[int] = []  # characters each edit's animation message sent as `unchanged`
        self.verdicts_ms: list[float] = []  # ms from each edit's animation to its story verdicts
        self.diagnostics_bytes: list[int] = []  # bytes of each edit's diagnostics deltas
        self.last_size = 0  # characters of the last message received
        self._diag_bytes = 0
        self._stack = contextlib.ExitStack()
        self.ws = self._stack.enter_context(
            connect(f"{ws_base}/api/documents/{doc_id}/live?wire=binary", max_size=None)
        )
        state = self.until(lambda m: m["type"] == "state")
        self.text, self.version = state["text"], state["version"]
        self.last_animation = self.until(lambda m: m["type"] == "animation" and m["version"] == self.version)

    def until(self, wanted: Any, timeout: float = 600.0) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        while True:
            raw = self.ws.recv(timeout=max(deadline - time.monotonic(), 0.01))
            size = len(raw if isinstance(raw, bytes) else raw.encode("utf-8"))  # the bytes that came
            if isinstance(raw, bytes) and raw[:4] == animwire.TEXT_MAGIC:  # a compressed JSON message
                raw = animwire.decompress_text(raw)
            msg = self._read_frame(raw) if isinstance(raw, bytes) else json.loads(raw)
            self.last_size = size
            if isinstance(raw, str) and msg["type"] == "diagnostics":
                self._diag_bytes += size
            self.received_bytes += size
            self.bytes_by_type[msg["type"]] = self.bytes_by_type.get(msg["type"], 0) + size
            if msg["type"] == "error":
                raise RuntimeError(f"gateway error {msg['code']}: {msg['message']}")
            if wanted(msg):
                return msg

    def _read_frame(self, raw: bytes) -> dict[str, Any]:
        """A binary animation frame as a message; patched characters are rebuilt from the held ones."""
        header, blobs = animwire.unpack(raw)
        held: dict[str, Any] = {}
        for c in header["characters"]:
            if c.get("unchanged"):
                frames = self.held.get(c["hash"])
            else:
                base = self.held.get(c["patch"]) if c.get("patch") else None
                if c.get("patch") and base is None:
                    raise RuntimeError(f"patch of {c['name']} against a version this client does not hold")
                frames = animwire.entry_frames(c, blobs, base)
            if frames is None:
                raise RuntimeError(f"{c['name']} sent unchanged, but this client does not hold it")
            held[c["hash"]] = frames
        self.held = held
        return dict(header)

    def edit_to_animation(self, start: int, end: int, text: str) -> float:
        """Send one edit; milliseconds until the animation of the version it produced arrives."""
        t0 = time.perf_counter()
        self.ws.send(
            json.dumps(
                {
                    "type": "edit",
                    "base_version": self.version,
                    "changes": [{"start": start, "end": end, "text": text}],
                }
            )
        )
        ack = self.until(lambda m: m["type"] in ("ack", "stale"))
        if ack["type"] == "stale":
            raise RuntimeError("the benchmark's edit was stale")
        self.last_animation = self.until(
            lambda m: m["type"] == "animation" and m["version"] == ack["version"]
        )
        elapsed = (time.perf_counter() - t0) * 1000.0
        self.animation_kb.append(self.last_size / 1024.0)
        # the story verdicts follow the animation as their own diagnostics delta: wait for them, so the
        # next edit does not share the CPU with them (and their bytes count for this edit)
        self.until(
            lambda m: (
                m["type"] == "diagnostics" and m["version"] == ack["version"] and not m["verdicts_pending"]
            ),
            timeout=120.0,
        )
        self.verdicts_ms.append((time.perf_counter() - t0) * 1000.0 - elapsed)
        self.diagnostics_bytes.append(self._diag_bytes)
        self._diag_bytes = 0
        self.overheads.append(elapsed - float(self.last_animation["stats"]["compute_ms"]))
        self.unchanged.append(sum(1 for c in self.last_animation["characters"] if c.get("unchanged")))
        self.text = self.text[:start] + text + self.text[end:]
        self.version = ack["version"]
        return elapsed

    def swap_word(self, old: str, new: str, occurrence: int) -> float:
        spots = [i for i in range(len(self.text)) if self.text.startswith(old, i)]
        if not spots:
            raise ValueError(f"{old!r} is not in the document")
        i = spots[occurrence % len(spots)]
        return self.edit_to_animation(i, i + len(old), new)

    def close(self) -> None:
        self._stack.close()


def run(reps: int, backend: str, progress: bool, budget_s: float | None = None) -> dict[str, Any]:
    """Measure; with budget_s, each kind of edit stops after that many seconds (at least one edit each)."""
    import httpx
    from tqdm import tqdm

    from services.gateway.server import GatewayThread
    from services.gateway.settings import Settings

    tmp = tempfile.TemporaryDirectory(prefix="wana-bench-edit-")
    settings = Settings(db=Path(tmp.name) / "sessions.sqlite", backend=backend, seed=SEED)
    gateway = GatewayThread(settings).start()
    base, ws_base = gateway.base_url, gateway.ws_url
    try:
        http = httpx.Client(base_url=base, timeout=600)
        warm = LiveClient(ws_base, http.post("/api/documents", json={"text": WARM_UP}).json()["doc_id"])
        warm.close()

        # cold full document: a new document holding the whole text (nothing memoised for it), from
        # opening its WebSocket to its first animation message
        doc_id = http.post("/api/documents", json={"text": document()}).json()["doc_id"]
        t0 = time.perf_counter()
        client = LiveClient(ws_base, doc_id)
        full_ms = (time.perf_counter() - t0) * 1000.0
        anim = client.last_animation

        action_ms: list[float] = []
        scene_ms: list[float] = []
        bar = tqdm(total=3 * reps, desc="edits", disable=not progress, unit="edit")
        started = time.monotonic()
        for k in range(reps):  # walks -> runs in the next action sentence, then back
            if budget_s is not None and action_ms and time.monotonic() - started > budget_s:
                break
            old, new, occurrence = ("walks", "runs", k // 2) if k % 2 == 0 else ("runs", "walks", 0)
            action_ms.append(client.swap_word(old, new, occurrence))
            bar.update()
        if "runs" in client.text:  # leave the action sentences as written
            client.swap_word("runs", "walks", 0)
        late_ms: list[float] = []
        late_kib: list[float] = []
        late_unchanged: list[int] = []
        started = time.monotonic()
        for k in range(reps):
            if budget_s is not None and late_ms and time.monotonic() - started > budget_s:
                break
            old, new = ("Tom walks to the desk", "Tom runs to the desk")[:: 1 if k % 2 == 0 else -1]
            late_ms.append(client.swap_word(old, new, 0))
            late_kib.append(client.animation_kb.pop())
            late_unchanged.append(client.unchanged.pop())
            client.overheads.pop()
            bar.update()
        if "Tom runs to the desk" in client.text:
            client.swap_word("Tom runs to the desk", "Tom walks to the desk", 0)
        started = time.monotonic()
        places = [("window", "door"), ("door", "window")]
        for k in range(reps):
            if budget_s is not None and scene_ms and time.monotonic() - started > budget_s:
                break
            old, new = places[k % 2]
            scene_ms.append(client.swap_word(old, new, 0))
            bar.update()
        client.close()
        # bytes per action edit in a 3-character document: every byte received from the edit to its animation
        # (at least three edits, so the p50 is a middle one)
        three = LiveClient(
            ws_base, http.post("/api/documents", json={"text": three_character_document()}).json()["doc_id"]
        )
        edit_bytes: list[int] = []
        by_type: list[dict[str, int]] = []
        started = time.monotonic()
        for k in range(reps):
            if budget_s is not None and len(edit_bytes) >= 3 and time.monotonic() - started > budget_s:
                break
            old, new, occurrence = ("walks", "runs", k // 2) if k % 2 == 0 else ("runs", "walks", 0)
            before, types_before = three.received_bytes, dict(three.bytes_by_type)
            three.swap_word(old, new, occurrence)
            edit_bytes.append(three.received_bytes - before)
            by_type.append({t: n - types_before.get(t, 0) for t, n in three.bytes_by_type.items()})
            bar.update()
        three.close()
        bar.close()
        http.close()
    finally:
        gateway.stop()
        tmp.cleanup()
    return {
        "full_ms": full_ms,
        "action": np.asarray(action_ms),
        "scene": np.asarray(scene_ms),
        "late": np.asarray(late_ms),
        "late_kib": np.asarray(late_kib),
        "late_unchanged": np.asarray(late_unchanged),
        "unavailable": anim.get("unavailable", {}),
        "overhead": np.asarray(client.overheads),
        "animation_kb": np.asarray(client.animation_kb),
        "unchanged": np.asarray(client.unchanged),
        "characters": len(anim["characters"]),
        "objects": len(anim["objects"]),
        "frames": anim["frames"],
        "edit_bytes": np.asarray(edit_bytes),
        "edit_bytes_by_type": {
            t: int(np.percentile([b.get(t, 0) for b in by_type], 50))
            for t in sorted({*(k for b in by_type for k in b)})
        },
        "verdicts_ms": np.asarray(client.verdicts_ms),
        "diagnostics_bytes": np.asarray(client.diagnostics_bytes),
    }


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument(
        "--quick",
        action="store_true",
        help="at most 5 edits of each kind and 5 s of edits per kind, instead of 30 edits",
    )
    p.add_argument("--reps", type=int, default=None, help="edits of each kind (overrides --quick)")
    p.add_argument(
        "--backend",
        choices=("inprocess", "embedded", "auto"),
        default="inprocess",
        help="how the orchestrator reaches the services (default inprocess: handler calls)",
    )
    p.add_argument("--json", type=Path, default=None, metavar="PATH", help="write the numbers as JSON here")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    args = p.parse_args(argv)
    reps = args.reps or (5 if args.quick else 30)
    r = run(reps, args.backend, not args.no_progress, budget_s=5.0 if args.quick and not args.reps else None)
    action_p50, action_p95 = np.percentile(r["action"], [50, 95])
    scene_p50, scene_p95 = np.percentile(r["scene"], [50, 95])
    ratio = float(action_p50 / r["full_ms"]) if r["full_ms"] > 0 else float("nan")
    print(
        f"\nedit -> animation over the gateway WebSocket, 20 sentences, {reps} edits each at most, backend {args.backend}"
    )
    print(f"measured {len(r['action'])} action edits and {len(r['scene'])} scene edits")
    print(f"result: {r['objects']} objects, {r['characters']} characters, {r['frames']} frames")
    if r["unavailable"]:
        print("stages not available in this build: " + ", ".join(sorted(r["unavailable"])))
    print(f"{'measure':<28}{'p50 ms':>10}{'p95 ms':>10}{'target':>14}")
    print(f"{'action edit (one word)':<28}{action_p50:>10.1f}{action_p95:>10.1f}{'p50 <= 150':>14}")
    print(f"{'scene edit (one word)':<28}{scene_p50:>10.1f}{scene_p95:>10.1f}{'':>14}")
    late_p50 = late_kib_p50 = float("nan")
    if len(r["late"]):
        late_p50, late_p95 = np.percentile(r["late"], [50, 95])
        late_kib_p50 = float(np.percentile(r["late_kib"], 50))
        print(f"{'late action edit (Tom)':<28}{late_p50:>10.1f}{late_p95:>10.1f}{'':>14}")
    print(f"{'full document (cold)':<28}{r['full_ms']:>10.1f}{'':>10}{'':>14}")
    print(f"{'ratio incremental / full':<28}{ratio:>10.3f}{'':>10}{'<= 0.1':>14}")
    if len(r["overhead"]):
        o50, o95 = np.percentile(r["overhead"], [50, 95])
        print(f"{'gateway share (not compute)':<28}{o50:>10.1f}{o95:>10.1f}{'':>14}")
        k50, k95 = np.percentile(r["animation_kb"], [50, 95])
        print(f"{'animation message (KiB)':<28}{k50:>10.1f}{k95:>10.1f}{'':>14}")
        v50, v95 = np.percentile(r["verdicts_ms"], [50, 95])
        print(f"{'animation -> verdicts':<28}{v50:>10.1f}{v95:>10.1f}{'':>14}")
        d50 = float(np.percentile(r["diagnostics_bytes"], 50))
        print(f"diagnostics deltas per edit: p50 {d50 / 1000:.1f} kB")
        print(
            f"characters sent as unchanged: {int(r['unchanged'].sum())} of "
            f"{len(r['unchanged']) * r['characters']} over {len(r['unchanged'])} action and scene edits "
            "(their timing is coupled in this document)"
        )
    if len(r["late"]):
        print(
            f"late action edits: {int(r['late_unchanged'].sum())} of {len(r['late']) * r['characters']} "
            f"characters sent as unchanged; animation message p50 {late_kib_p50:.1f} KiB"
        )
    if len(r["edit_bytes"]):
        b50, b95 = np.percentile(r["edit_bytes"], [50, 95])
        print(
            f"bytes per action edit, 3 characters: p50 {b50 / 1000:.1f} kB, p95 {b95 / 1000:.1f} kB "
            f"over {len(r['edit_bytes'])} edits (target p50 <= 50 kB)"
        )
        print(
            "  by message type, p50: "
            + ", ".join(f"{t} {n / 1000:.1f} kB" for t, n in r["edit_bytes_by_type"].items() if n)
        )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        out = {
            "action_edit_p50_ms": round(float(action_p50), 3),
            "scene_edit_p50_ms": round(float(scene_p50), 3),
            "full_ms": round(float(r["full_ms"]), 3),
            "ratio": round(ratio, 4),
        }
        if len(r["overhead"]):  # added keys (the four above are stable)
            out["gateway_share_p50_ms"] = round(float(np.percentile(r["overhead"], 50)), 3)
            out["animation_message_kib_p50"] = round(float(np.percentile(r["animation_kb"], 50)), 1)
            out["verdicts_after_animation_p50_ms"] = round(float(np.percentile(r["verdicts_ms"], 50)), 3)
            out["diagnostics_bytes_per_edit_p50"] = int(np.percentile(r["diagnostics_bytes"], 50))
            out["unchanged_character_share"] = round(
                float(r["unchanged"].sum()) / max(len(r["unchanged"]) * r["characters"], 1), 3
            )
        if len(r["edit_bytes"]):
            out["bytes_per_action_edit_p50"] = int(np.percentile(r["edit_bytes"], 50))
            out["bytes_per_action_edit_by_type_p50"] = r["edit_bytes_by_type"]
        if len(r["late"]):
            out["late_action_edit_p50_ms"] = round(float(late_p50), 3)
            out["late_action_animation_kib_p50"] = round(late_kib_p50, 1)
        args.json.write_text(json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
