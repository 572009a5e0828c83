"""Evaluate the NLP stage: SSG extraction against hand-written gold, and the parser on UD English-EWT.

Usage:
    .venv/bin/python eval/nlp.py [--split test|dev|styles|fresh|all] [--quick] [--json PATH] [--verbose]

Gold: eval/data/nlp/{dev,test}.txt, and styles.txt (other people's writing: children's stories,
screenplays, quest text, stage directions; items tagged "K <construction>", scored per construction
as well) and fresh.txt (more of the same, written before the parser was changed for them). Format in eval/data/nlp/README.md. Each item (a one- to
five-sentence text) goes through the real pipeline: split -> parse -> resolve. Predictions and gold
are pooled per item and compared as multisets:
  objects    (category, count)                      attributes (category, knob, value)
  relations  (subject category, relation, anchor category)
  actions    (character, action, target-or-destination)   action_args (character, action, field, value)
  commands   (kind, value, seconds)   social (kind, label, subjects)   rooms (room type)
Parser scores: POS accuracy, UAS, LAS on the EWT test set (spaCy tokenization, punctuation excluded);
read from ../shared/data (WANA_SHARED_DATA); --quick scores its first 300 sentences.
JSON keys (test split unless --split): objects_f1, relations_f1, actions_f1, uas, las, pos.
Targets: objects and actions F1 >= 0.95, relations F1 >= 0.90; POS >= 0.93, UAS >= 0.85, LAS >= 0.80.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from proto.ssg import SentenceGraph  # noqa: E402

DATA = REPO / "eval" / "data" / "nlp"
SHARED = Path(os.environ.get("WANA_SHARED_DATA", REPO.parent / "shared" / "data"))
EWT_TEST = SHARED / "ud_english_ewt" / "en_ewt-ud-test.conllu"
ARG_FIELDS = {"m": "manner", "i": "instrument", "s": "duration_s"}
KINDS = ("objects", "attributes", "relations", "actions", "action_args", "commands", "social", "rooms")


CONSTRUCTIONS = (
    "relative_clause",
    "facing",
    "titled_name",
    "phrasal_verb",
    "time_phrase",
    "quoted_speech",
    "plural",
    "new_object",
    "with_phrase",
    "common_verb",
    "body_part",
)


@dataclass
class Item:
    text: str
    line: int
    gold: dict[str, Counter] = field(default_factory=lambda: {k: Counter() for k in KINDS})
    constructions: tuple[str, ...] = ()
    source: str = ""


def _name(value: str) -> str:
    """A name in a gold line: "Aunt_May" -> "Aunt May", "each_other" -> "each other"."""
    return value.replace("_", " ") if value[:1].isupper() or value == "each_other" else value


def _num(value: str) -> str:
    return f"{float(value):g}"


def load_items(path: Path) -> list[Item]:
    """Read a gold file: items start with "T <text>" ("\\n" = newline), gold lines follow."""
    items: list[Item] = []
    for lineno, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        tag, _, rest = line.partition(" ")
        if tag == "T":
            items.append(Item(text=rest.replace("\\n", "\n"), line=lineno, source=path.stem))
            continue
        if not items:
            raise ValueError(f"{path}:{lineno}: gold line before any 'T' line")
        gold = items[-1].gold
        parts = rest.split()
        if tag == "O":
            category, count = parts[0], 1
            for p in parts[1:]:
                key, _, value = p.partition("=")
                if key == "n":
                    count = int(value)
                else:
                    gold["attributes"][(category, key, value)] += 1
            gold["objects"][(category, count)] += 1
        elif tag == "R":
            gold["relations"][tuple(parts[:3])] += 1
        elif tag == "K":
            unknown = [c for c in parts if c not in CONSTRUCTIONS]
            if unknown:
                raise ValueError(f"{path}:{lineno}: unknown construction {unknown}")
            items[-1].constructions = tuple(parts)
        elif tag == "A":
            character, action = _name(parts[0]), parts[1]
            kv = {k: _name(v) for k, v in (p.split("=", 1) for p in parts[2:])}
            gold["actions"][(character, action, kv.get("t") or kv.get("d", ""))] += 1
            for key, name in ARG_FIELDS.items():
                if key in kv:
                    value = _num(kv[key]) if key == "s" else kv[key]
                    gold["action_args"][(character, action, name, value)] += 1
        elif tag == "C":
            seconds = _num(parts[2]) if len(parts) > 2 else "0"
            gold["commands"][(parts[0], "" if parts[1] == "-" else parts[1], seconds)] += 1
        elif tag == "S":
            gold["social"][(parts[0], parts[1], tuple(sorted(_name(n) for n in parts[2].split(","))))] += 1
        elif tag == "room":
            gold["rooms"][parts[0]] += 1
        else:
            raise ValueError(f"{path}:{lineno}: unknown gold tag {tag!r}")
    return items


def predicted(graphs: list[SentenceGraph]) -> dict[str, Counter]:
    """Pool one item's graphs into the multisets the gold uses."""
    out: dict[str, Counter] = {k: Counter() for k in KINDS}
    categories: dict[str, str] = {}
    counts: dict[str, int] = {}
    attributes: dict[str, dict[str, str]] = {}
    for g in graphs:
        for o in g.objects:
            if o.id not in categories:
                categories[o.id], counts[o.id] = o.category, o.count
                attributes[o.id] = {}
            for k, v in o.attributes.items():
                attributes[o.id].setdefault(k, v)
    for oid, cat in categories.items():
        out["objects"][(cat, counts[oid])] += 1
        for k, v in attributes[oid].items():
            out["attributes"][(cat, k, v)] += 1
    relations = {
        (categories.get(r.subject, r.subject), r.relation, categories.get(r.object, r.object))
        for g in graphs
        for r in g.relations
    }
    out["relations"].update(relations)
    for g in graphs:
        for c in g.characters:
            for a in c.actions:
                if not a.action:
                    continue  # a verb no clip shows ("knits"): its diagnostic says so, it is no action
                where = a.target or a.destination
                out["actions"][(c.name, a.action, categories.get(where, where))] += 1
                if a.manner:
                    out["action_args"][(c.name, a.action, "manner", a.manner)] += 1
                if a.instrument:
                    out["action_args"][
                        (c.name, a.action, "instrument", categories.get(a.instrument, a.instrument))
                    ] += 1
                if a.duration_s:
                    out["action_args"][(c.name, a.action, "duration_s", _num(str(a.duration_s)))] += 1
        for cmd in g.commands:
            out["commands"][(cmd.kind, cmd.value, _num(str(cmd.seconds)))] += 1
        for s in g.social:
            out["social"][(s.kind, s.label, tuple(sorted(s.subjects)))] += 1
        if g.room_type:
            out["rooms"][g.room_type] += 1
    out["rooms"] = Counter(set(out["rooms"]))
    return out


def prf(gold: Counter, pred: Counter) -> tuple[float, float, float]:
    tp = sum((gold & pred).values())
    p = tp / sum(pred.values()) if pred else (1.0 if not gold else 0.0)
    r = tp / sum(gold.values()) if gold else (1.0 if not pred else 0.0)
    f = 2 * p * r / (p + r) if p + r else 0.0
    return p, r, f


def evaluate_ssg(
    items: list[Item], verbose: bool = False
) -> tuple[dict[str, tuple[float, float, float, int, int]], int]:
    from services.nlp.parse import parse_document
    from services.nlp.segment import split_sentences

    gold_all = {k: Counter() for k in KINDS}
    pred_all = {k: Counter() for k in KINDS}
    n_sentences = 0
    for item in items:
        n_sentences += len(split_sentences(item.text))
        pred = predicted(parse_document(item.text))
        item_pred[item.line, item.source] = pred
        for k in KINDS:
            # keep multisets per item apart so that equal tuples of two items never cross-match
            gold_all[k].update({(item.line, *_astuple(t)): n for t, n in item.gold[k].items()})
            pred_all[k].update({(item.line, *_astuple(t)): n for t, n in pred[k].items()})
        if verbose:
            for k in KINDS:
                missing = item.gold[k] - pred[k]
                extra = pred[k] - item.gold[k]
                if missing or extra:
                    print(f"line {item.line} {item.text!r} {k}: missing {dict(missing)} extra {dict(extra)}")
    table = {}
    for k in KINDS:
        p, r, f = prf(gold_all[k], pred_all[k])
        table[k] = (p, r, f, sum(gold_all[k].values()), sum(pred_all[k].values()))
    return table, n_sentences


item_pred: dict[tuple[int, str], dict[str, Counter]] = {}  # filled by evaluate_ssg


def construction_scores(items: list[Item]) -> dict[str, tuple[int, float, float]]:
    """Per construction: (items, F1 over every kind pooled, share of items entirely right).

    Run after evaluate_ssg (which keeps each item's prediction)."""
    out: dict[str, tuple[int, float, float]] = {}
    for name in CONSTRUCTIONS:
        chosen = [it for it in items if name in it.constructions]
        if not chosen:
            continue
        gold: Counter = Counter()
        pred: Counter = Counter()
        exact = 0
        for it in chosen:
            p = item_pred[it.line, it.source]
            for k in KINDS:
                gold.update({(it.line, k, *_astuple(t)): n for t, n in it.gold[k].items()})
                pred.update({(it.line, k, *_astuple(t)): n for t, n in p[k].items()})
            exact += all(it.gold[k] == p[k] for k in KINDS)
        out[name] = (len(chosen), prf(gold, pred)[2], exact / len(chosen))
    return out


def _astuple(t: object) -> tuple:
    return t if isinstance(t, tuple) else (t,)


def evaluate_parser(quick: bool) -> dict[str, float] | None:
    if not EWT_TEST.exists():
        return None
    from services.nlp.pipeline import evaluate_treebank

    return evaluate_treebank(EWT_TEST, limit=300 if quick else 0)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(
        "--split",
        choices=("test", "dev", "styles", "fresh", "all"),
        default="test",
        help="gold split (default test; styles: other people's writing; fresh: more of it, written "
        "before the parser was changed for it; all: the four)",
    )
    ap.add_argument("--quick", action="store_true", help="first 300 EWT test sentences only (< 30 s)")
    ap.add_argument(
        "--json", type=Path, help="write objects_f1, relations_f1, actions_f1, uas, las, pos here"
    )
    ap.add_argument("--verbose", action="store_true", help="print each item's misses and extras")
    args = ap.parse_args(argv)
    splits = ("dev", "test", "styles", "fresh") if args.split == "all" else (args.split,)
    items = [it for s in splits for it in load_items(DATA / f"{s}.txt")]
    t0 = time.perf_counter()
    table, n_sentences = evaluate_ssg(items, args.verbose)
    t_ssg = time.perf_counter() - t0
    print(f"SSG extraction, split {args.split}: {len(items)} items, {n_sentences} sentences ({t_ssg:.1f} s)")
    print(f"{'kind':<12} {'P':>6} {'R':>6} {'F1':>6} {'gold':>5} {'pred':>5}")
    for k in KINDS:
        p, r, f, g, n = table[k]
        print(f"{k:<12} {p:6.3f} {r:6.3f} {f:6.3f} {g:5d} {n:5d}")
    constructions = construction_scores(items)
    if constructions:
        print(f"per construction ({args.split}): F1 over all kinds, share of items entirely right")
        print(f"{'construction':<16} {'items':>5} {'F1':>6} {'exact':>6}")
        for name, (n, f1, exact) in constructions.items():
            print(f"{name:<16} {n:5d} {f1:6.3f} {exact:6.3f}")
    parser = evaluate_parser(args.quick)
    if parser is None:
        print(f"parser: {EWT_TEST} absent, POS/UAS/LAS not measured")
    else:
        print(
            f"parser on EWT test{' (first 300 sentences)' if args.quick else ''}: "
            f"{int(parser['sentences'])} sentences"
        )
        print(f"{'pos':<6} {'uas':>6} {'las':>6} {'tag':>6} {'lemma':>6}")
        print(
            f"{parser['pos']:<6.3f} {parser['uas']:6.3f} {parser['las']:6.3f} {parser['tag']:6.3f} "
            f"{parser['lemma']:6.3f}"
        )
    if args.json:
        out = {
            "objects_f1": table["objects"][2],
            "relations_f1": table["relations"][2],
            "actions_f1": table["actions"][2],
            "constructions_f1": {name: v[1] for name, v in constructions.items()},
            "uas": parser["uas"] if parser else None,
            "las": parser["las"] if parser else None,
            "pos": parser["pos"] if parser else None,
        }
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
