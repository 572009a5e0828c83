"""Benchmark the NLP stage: parse latency per sentence (pipeline + SSG extraction), cold and batched.

Usage:
    .venv/bin/python bench/nlp.py [--quick] [--json PATH] [--repeats N]

Sentences: the gold sentences of eval/data/nlp (scene, action, command, multi-character). Each
timed call is ``parse_sentence`` on a sentence it has not seen (the per-text cache is cleared before
every call, so the spaCy pipeline really runs); one thread; the pipeline is loaded before timing.
Also reported: pipeline load time and a whole document (100 sentences) through parse_document.
JSON keys: p50_ms, p95_ms. Target: p50_ms <= 5.
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


def percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    k = min(len(ordered) - 1, max(0, round(q / 100 * (len(ordered) - 1))))
    return ordered[k]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="one pass over 80 sentences (< 30 s)")
    ap.add_argument("--json", type=Path, help="write p50_ms and p95_ms here")
    ap.add_argument("--repeats", type=int, default=3, help="passes over the sentences (full run)")
    args = ap.parse_args(argv)

    from services.nlp.parse import clear_cache, parse_document, parse_sentence
    from services.nlp.pipeline import get_nlp

    t0 = time.perf_counter()
    get_nlp()
    load_s = time.perf_counter() - t0
    texts = sentences()
    if args.quick:
        texts = texts[:80]
    repeats = 1 if args.quick else max(1, args.repeats)
    parse_sentence("Eve sits on the chair.")  # warm-up: lexicon, action library, compounds
    times: list[float] = []
    for _ in range(repeats):
        for text in texts:
            clear_cache()
            t = time.perf_counter()
            parse_sentence(text, "s", 0)
            times.append((time.perf_counter() - t) * 1000.0)
    document = "\n".join(texts[:100])
    clear_cache()
    t = time.perf_counter()
    graphs = parse_document(document)
    doc_ms = (time.perf_counter() - t) * 1000.0
    p50, p95 = statistics.median(times), percentile(times, 95)
    print(f"NLP parse latency: {len(texts)} sentences x {repeats}, pipeline loaded in {load_s:.2f} s")
    print(f"{'metric':<28} {'value':>10}")
    print(f"{'p50_ms (per sentence)':<28} {p50:10.2f}")
    print(f"{'p95_ms (per sentence)':<28} {p95:10.2f}")
    print(f"{'mean_ms':<28} {statistics.fmean(times):10.2f}")
    print(f"{'document_ms':<28} {doc_ms:10.1f}  ({len(graphs)} sentences, split+parse+resolve)")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"p50_ms": p50, "p95_ms": p95}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
