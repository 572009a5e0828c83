"""Which sentence checks flip between two runs of eval/story.py (A -> B): ok -> failed and failed -> ok.

Usage:
    .venv/bin/python eval/story_diff.py A.json B.json [--more A2.json B2.json ...] [--json PATH]

Both files are ``eval/story.py --json`` outputs. A check is keyed by story, sentence id, check name, character
and its rank among that sentence's results with the same name and character (a sentence checks each object
or partner once), so a check that exists in one run only is listed as appeared/vanished rather than matched
with another. Prints one row per flipped check (story | sentence | check | character | A -> B | reasons) and
the counts; a story that crashed in one run shows as its error. JSON keys: flips (rows with story, sentence,
text, check, character, a, b, reason_a, reason_b), broke, fixed, appeared, vanished, sentences_broke,
sentences_fixed, fidelity_a, fidelity_b.

``--more`` adds pairs run with other seeds (``eval/story.py --seed N`` on both sides): one layout drawn by the
optimiser's annealing decides many checks, so a single seed's difference can be the draw. Then the table also
gives each pair's sentence fidelity, their means, and the checks that fail at least two seeds more often on
one side (``seeds`` in the JSON: pairs, fidelity_a, fidelity_b, mean_a, mean_b, leaning).
"""

from __future__ import annotations

import argparse
import collections
import json
import sys
from pathlib import Path
from typing import Any

Key = tuple[str, str, str, str, int]


def check_states(
    run: dict[str, Any],
) -> tuple[dict[Key, dict[str, Any]], dict[tuple[str, str], dict[str, Any]]]:
    """Every check of a story.py run keyed as the docstring says, and every sentence by (story, id)."""
    checks: dict[Key, dict[str, Any]] = {}
    sentences: dict[tuple[str, str], dict[str, Any]] = {}
    for story in run.get("per_story", []):
        name = story["story"]
        if story.get("error"):
            sentences[(name, "*")] = {"verdict": "crashed", "text": story["error"]}
            continue
        for sentence in story.get("per_sentence", []):
            sentences[(name, sentence["id"])] = sentence
            rank: collections.Counter[tuple[str, str]] = collections.Counter()
            for r in sentence.get("results", []):
                who = r.get("character", "")
                key = (name, sentence["id"], r["name"], who, rank[(r["name"], who)])
                rank[(r["name"], who)] += 1
                checks[key] = {**r, "text": sentence.get("text", "")}
    return checks, sentences


def diff(a: dict[str, Any], b: dict[str, Any]) -> dict[str, Any]:
    """The flips from run ``a`` to run ``b`` (see the module docstring for the keys)."""
    checks_a, sentences_a = check_states(a)
    checks_b, sentences_b = check_states(b)
    flips: list[dict[str, Any]] = []
    counts = collections.Counter[str]()
    for key in sorted(set(checks_a) | set(checks_b)):
        ra, rb = checks_a.get(key), checks_b.get(key)
        state_a = "-" if ra is None else ("ok" if ra["ok"] else "failed")
        state_b = "-" if rb is None else ("ok" if rb["ok"] else "failed")
        if state_a == state_b:
            continue
        kind = {("ok", "failed"): "broke", ("failed", "ok"): "fixed"}.get(
            (state_a, state_b), "appeared" if ra is None else "vanished"
        )
        counts[kind] += 1
        story, sid, check, who, _ = key
        flips.append({
            "story": story, "sentence": sid, "text": (rb or ra or {}).get("text", ""), "check": check,
            "character": who, "a": state_a, "b": state_b, "kind": kind,
            "reason_a": (ra or {}).get("reason", ""), "reason_b": (rb or {}).get("reason", ""),
        })  # fmt: skip
    for story_key in sorted(k for k in set(sentences_a) | set(sentences_b) if k[1] == "*"):
        crash_a, crash_b = sentences_a.get(story_key) or {}, sentences_b.get(story_key) or {}
        if crash_a.get("verdict") != crash_b.get("verdict"):
            flips.append({
                "story": story_key[0], "sentence": "*", "text": "", "check": "crash", "character": "",
                "a": crash_a.get("verdict", "ran"), "b": crash_b.get("verdict", "ran"), "kind": "crash",
                "reason_a": crash_a.get("text", ""), "reason_b": crash_b.get("text", ""),
            })  # fmt: skip

    def verdict(sentences: dict[tuple[str, str], dict[str, Any]], key: tuple[str, str]) -> str:
        return (sentences.get(key) or {}).get("verdict", "-")

    both = [k for k in sentences_a if k in sentences_b and k[1] != "*"]
    return {
        "flips": flips,
        **{kind: counts[kind] for kind in ("broke", "fixed", "appeared", "vanished")},
        "sentences_broke": sorted(
            f"{s} {i}"
            for s, i in both
            if verdict(sentences_a, (s, i)) == "ok" != verdict(sentences_b, (s, i))
        ),
        "sentences_fixed": sorted(
            f"{s} {i}"
            for s, i in both
            if verdict(sentences_b, (s, i)) == "ok" != verdict(sentences_a, (s, i))
        ),
        "fidelity_a": a.get("sentence_fidelity"),
        "fidelity_b": b.get("sentence_fidelity"),
    }


def over_seeds(pairs: list[tuple[dict[str, Any], dict[str, Any]]]) -> dict[str, Any]:
    """Sentence fidelity of each (a, b) pair, the means, and the checks failing >= 2 seeds more on one side."""
    fails: dict[str, collections.Counter[tuple[str, str, str, str]]] = {
        "a": collections.Counter(),
        "b": collections.Counter(),
    }
    for a, b in pairs:
        for side, run in (("a", a), ("b", b)):
            checks, _ = check_states(run)
            fails[side].update({k[:4] for k, r in checks.items() if not r["ok"]})
    fa = [float(a.get("sentence_fidelity") or 0.0) for a, _ in pairs]
    fb = [float(b.get("sentence_fidelity") or 0.0) for _, b in pairs]
    keys = set(fails["a"]) | set(fails["b"])
    leaning = [
        {
            "story": k[0],
            "sentence": k[1],
            "check": k[2],
            "character": k[3],
            "failed_a": fails["a"][k],
            "failed_b": fails["b"][k],
        }
        for k in sorted(keys, key=lambda k: (fails["a"][k] - fails["b"][k], k))
        if abs(fails["a"][k] - fails["b"][k]) >= 2
    ]
    return {
        "pairs": len(pairs),
        "fidelity_a": fa,
        "fidelity_b": fb,
        "mean_a": sum(fa) / len(fa),
        "mean_b": sum(fb) / len(fb),
        "leaning": leaning,
    }


def print_table(result: dict[str, Any], width: int = 90) -> None:
    """One row per flipped check, then the counts."""
    for f in result["flips"]:
        who = f" ({f['character']})" if f["character"] else ""
        print(f"{f['story']} | {f['sentence']} {f['text'][:60]} | {f['check']}{who} | {f['a']} -> {f['b']}")
        for side in ("a", "b"):
            if f[f"reason_{side}"]:
                print(f"    {side.upper()}: {f[f'reason_{side}'][:width]}")
    print(
        f"checks broke {result['broke']}, fixed {result['fixed']}, appeared {result['appeared']}, "
        f"vanished {result['vanished']}; sentences ok -> not {len(result['sentences_broke'])}, "
        f"not -> ok {len(result['sentences_fixed'])}; sentence fidelity {result['fidelity_a']} -> "
        f"{result['fidelity_b']}"
    )
    seeds = result.get("seeds")
    if seeds:
        print(
            f"over {seeds['pairs']} pairs: fidelity A {[round(f, 3) for f in seeds['fidelity_a']]} mean "
            f"{seeds['mean_a']:.3f}, B {[round(f, 3) for f in seeds['fidelity_b']]} mean {seeds['mean_b']:.3f}"
        )
        for row in seeds["leaning"]:
            who = f" ({row['character']})" if row["character"] else ""
            print(f"  failed A {row['failed_a']} / B {row['failed_b']} of {seeds['pairs']}: {row['story']} | "
                  f"{row['sentence']} | {row['check']}{who}")  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a", type=Path, help="the first eval/story.py --json output")
    ap.add_argument("b", type=Path, help="the second one")
    ap.add_argument("--more", type=Path, nargs=2, action="append", default=[], metavar=("A", "B"),
                    help="another pair of runs (another seed); repeatable")  # fmt: skip
    ap.add_argument("--json", type=Path, default=None, help="write the flips here")
    args = ap.parse_args(argv)
    pairs = [
        (json.loads(a.read_text()), json.loads(b.read_text())) for a, b in [(args.a, args.b), *args.more]
    ]
    result = diff(*pairs[0])
    if len(pairs) > 1:
        result["seeds"] = over_seeds(pairs)
    print_table(result)
    if args.json:
        args.json.write_text(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
