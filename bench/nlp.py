"""Benchmark the NLP stage: parse latency per sentence (pipeline + SSG extraction), cold and batched.

Usage:
    .venv/bin/python bench/nlp.py [--quick] [--json PATH] [--repeats N]

Sentences: the gold sentences of eval/data/nlp (scene, action, command, multi-character). Each
timed call is ``parse_sentence`` on a sentence it has not seen (the per-text cache is cleared before
every call, so the spaCy pipeline really runs); one thread; the pipeline is loaded before timing.
Also reported: the CPU time per call (``time.process_time``: what the sentence costs, whatever the
machine's load; wall time on a shared machine waits for the other processes too), pipeline load
time, a whole document (100 sentences) through parse_document, and did-you-mean per misspelling.
``--alternate`` also times the reference path (thinc's own tok2vec forward and blis ``gemm``
instead of :class:`services.nlp.fast_tok2vec.FastTok2Vec` and
:class:`services.nlp.matmul_ops.MatmulOps`), alternating passes with the shipped path in the same
run, so the two see the same machine load.
JSON keys: p50_ms, p95_ms, cpu_p50_ms, suggest_p50_ms (and reference_* with --alternate). Target: p50_ms <= 5.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))


def sentences() -> list[str]:
    from services.nlp.segment import split_sentences

    out: list[str] = []
    for split in ("dev", "test"):
        for line in (
            (REPO / "eval" / "data" / "nlp" / f"{split}.txt").read_text(encoding="utf-8").splitlines()
        ):
            if line.startswith("T "):
                text = line[2:].replace("\\n", "\n")
                out += [text[s:e] for s, e, _ in split_sentences(text)]
    return out


def suggest_times(n: int = 120) -> list[float]:
    """ms per did-you-mean over seeded misspellings (one letter dropped, doubled or swapped) of object
    and action words; the suggestion cache is cleared before each call."""
    import random

    from services.nlp import suggest

    rng = random.Random(5)
    words = sorted(suggest._object_words()) + sorted(suggest._verb_words())
    suggest.did_you_mean("chiar", "object")  # builds the vocabularies
    suggest.did_you_mean("sist", "action")
    out: list[float] = []
    for word in rng.sample(words, n):
        i = rng.randrange(len(word))
        typo = rng.choice(
            [
                word[:i] + word[i + 1 :],
                word[:i] + word[i] + word[i:],
                word[:i] + word[i + 1 : i + 2] + word[i] + word[i + 2 :],
            ]
        )
        suggest.suggestions.cache_clear()
        t = time.perf_counter()
        suggest.did_you_mean(typo, rng.choice(["object", "action"]))
        out.append((time.perf_counter() - t) * 1000.0)
    return out


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    k = min(len(ordered) - 1, max(0, round(q / 100 * (len(ordered) - 1))))
    return ordered[k]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="one pass over 80 sentences (< 30 s)")
    ap.add_argument("--json", type=Path, help="write p50_ms and p95_ms here")
    ap.add_argument("--repeats", type=int, default=3, help="passes over the sentences (full run)")
    ap.add_argument("--alternate", action="store_true", help="also time the reference path, alternating")
    args = ap.parse_args(argv)

    from services.nlp.parse import clear_cache, parse_document, parse_sentence
    from services.nlp.pipeline import get_nlp, use_fast_inference

    t0 = time.perf_counter()
    nlp = get_nlp()
    load_s = time.perf_counter() - t0
    texts = sentences()
    if args.quick:
        texts = texts[:80]
    repeats = 1 if args.quick else max(1, args.repeats)
    parse_sentence("Eve sits on the chair.")  # warm-up: lexicon, action library, compounds
    paths = ["shipped", "reference"] if args.alternate else ["shipped"]
    times: dict[str, list[float]] = {p: [] for p in paths}
    cpu: dict[str, list[float]] = {p: [] for p in paths}
    for _ in range(repeats):
        for path in paths * (2 if args.alternate else 1):  # A B A B: the same minute for both
            fast = use_fast_inference(nlp, path == "shipped")
            if path == "shipped" and not fast:
                print("note: the fast tok2vec forward does not apply to this model; thinc's runs")
            for text in texts:
                clear_cache()
                c, t = time.process_time(), time.perf_counter()
                parse_sentence(text, "s", 0)
                times[path].append((time.perf_counter() - t) * 1000.0)
                cpu[path].append((time.process_time() - c) * 1000.0)
    use_fast_inference(nlp, True)
    document = "\n".join(texts[:100])
    clear_cache()
    t = time.perf_counter()
    graphs = parse_document(document)
    doc_ms = (time.perf_counter() - t) * 1000.0
    passes = repeats * (2 if args.alternate else 1)
    print(f"NLP parse latency: {len(texts)} sentences x {passes}, pipeline loaded in {load_s:.2f} s")
    print(f"{'metric':<28} " + " ".join(f"{p:>10}" for p in paths))
    rows = {
        "p50_ms": {p: statistics.median(times[p]) for p in paths},
        "p95_ms": {p: percentile(times[p], 95) for p in paths},
        "mean_ms": {p: statistics.fmean(times[p]) for p in paths},
        "cpu_p50_ms": {p: statistics.median(cpu[p]) for p in paths},
    }
    for name, row in rows.items():
        print(f"{name + ' (per sentence)':<28} " + " ".join(f"{row[p]:10.2f}" for p in paths))
    print(f"{'document_ms':<28} {doc_ms:10.1f}  ({len(graphs)} sentences, split+parse+resolve)")
    suggest_ms = suggest_times()
    print(
        f"{'suggest_p50_ms':<28} {statistics.median(suggest_ms):10.3f}  (did-you-mean, {len(suggest_ms)} misspellings)"
    )
    if args.json:
        out = {k: rows[k]["shipped"] for k in ("p50_ms", "p95_ms", "cpu_p50_ms")}
        out["suggest_p50_ms"] = statistics.median(suggest_ms)
        if args.alternate:
            out.update({f"reference_{k}": rows[k]["reference"] for k in ("p50_ms", "p95_ms", "cpu_p50_ms")})
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
