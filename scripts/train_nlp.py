"""Rebuild wana's English pipeline (models/nlp/en_wana) from UD English-EWT plus the domain treebank.

Steps (each skips work that is already done unless --force):
  1. corpus   regenerate corpus/domain/domain-{train,test}.conllu from its templates (seeded)
  2. convert  `spacy convert` the EWT and domain CoNLL-U files into build/nlp/corpus/*.spacy
  3. train    `spacy train services/nlp/train_config.cfg` on EWT-train + 3 x domain-train, dev = EWT-dev
              (CPU, one thread, nice 10; seed, step budget and parameter averaging in the config)
  4. finetune optional (FINETUNE_STEPS > 0): continue from model-best at a lower learning rate;
              off for the shipped recipe (averaging is on from the start), so this step only
              removes a stale build/nlp/finetuned
  5. package  add wana's lookup lemmatizer (tables built from the treebanks' lemmas), disable the
              senter (the parser sets sentence boundaries), write models/nlp/en_wana (<= 30 MB)
  6. evaluate POS / UAS / LAS on EWT-test and the domain test split -> models/nlp/en_wana/scores.json

Usage:
    .venv/bin/python scripts/train_nlp.py              # all steps
    .venv/bin/python scripts/train_nlp.py --steps package evaluate
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

SHARED = Path(os.environ.get("WANA_SHARED_DATA", REPO.parent / "shared" / "data"))
EWT = SHARED / "ud_english_ewt"
BUILD = REPO / "build" / "nlp"
CORPUS = BUILD / "corpus"
TRAIN_DIR = BUILD / "train"
CONFIG = REPO / "services" / "nlp" / "train_config.cfg"
DOMAIN = REPO / "corpus" / "domain"
MODEL_OUT = REPO / "models" / "nlp" / "en_wana"
DOMAIN_UPSAMPLE = 3
FINETUNE_STEPS = 0  # 0 = no fine-tuning pass (the shipped recipe)
FINETUNE_LEARN_RATE = 0.0003
STEPS = ("corpus", "convert", "train", "finetune", "package", "evaluate")


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env.update(OMP_NUM_THREADS="1", MKL_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", PYTHONHASHSEED="0")
    return env


def _run(cmd: list[str]) -> None:
    print("+", " ".join(str(c) for c in cmd), flush=True)
    subprocess.run(cmd, check=True, env=_env())


def step_corpus(force: bool) -> None:
    _run([sys.executable, str(DOMAIN / "generate.py")])


def step_convert(force: bool) -> None:
    CORPUS.mkdir(parents=True, exist_ok=True)
    sources = [EWT / f"en_ewt-ud-{s}.conllu" for s in ("train", "dev", "test")]
    sources += [DOMAIN / "domain-train.conllu", DOMAIN / "domain-test.conllu"]
    for src in sources:
        if not src.exists():
            raise SystemExit(f"missing {src}: set WANA_SHARED_DATA to the shared data folder")
        out = CORPUS / (src.stem + ".spacy")
        if out.exists() and not force and out.stat().st_mtime >= src.stat().st_mtime:
            continue
        _run([sys.executable, "-m", "spacy", "convert", "-c", "conllu", "-n", "10", str(src), str(CORPUS)])
    if TRAIN_DIR.exists():
        shutil.rmtree(TRAIN_DIR)
    TRAIN_DIR.mkdir(parents=True)
    shutil.copy(CORPUS / "en_ewt-ud-train.spacy", TRAIN_DIR / "ewt-train.spacy")
    for i in range(DOMAIN_UPSAMPLE):
        shutil.copy(CORPUS / "domain-train.spacy", TRAIN_DIR / f"domain-train-{i}.spacy")


def step_train(force: bool) -> None:
    out = BUILD / "trained"
    if (out / "model-best").exists() and not force:
        print(f"{out / 'model-best'} exists; --force to retrain")
        return
    _run(
        [
            "nice",
            "-n",
            "10",
            sys.executable,
            "-m",
            "spacy",
            "train",
            str(CONFIG),
            "-o",
            str(out),
            "--paths.train",
            str(TRAIN_DIR),
            "--paths.dev",
            str(CORPUS / "en_ewt-ud-dev.spacy"),
        ]
    )


def step_finetune(force: bool) -> None:
    """Optionally continue from model-best with a lower learning rate and parameter averaging."""
    from spacy.util import load_config

    out = BUILD / "finetuned"
    if FINETUNE_STEPS <= 0:
        if out.exists():  # package must not pick up a model from an older recipe
            shutil.rmtree(out)
        print("FINETUNE_STEPS = 0: no fine-tuning pass")
        return
    if (out / "model-best").exists() and not force:
        print(f"{out / 'model-best'} exists; --force to redo")
        return
    source = BUILD / "trained" / "model-best"
    cfg = load_config(CONFIG)
    for name in cfg["nlp"]["pipeline"]:
        cfg["components"][name] = {"source": str(source)}
    cfg["training"]["max_steps"] = FINETUNE_STEPS
    cfg["training"]["eval_frequency"] = 250
    cfg["training"]["optimizer"]["learn_rate"] = FINETUNE_LEARN_RATE
    cfg["training"]["optimizer"]["use_averages"] = True
    cfg["training"]["batcher"]["size"] = 1000
    path = BUILD / "finetune.cfg"
    cfg.to_disk(path)
    _run(
        [
            "nice",
            "-n",
            "10",
            sys.executable,
            "-m",
            "spacy",
            "train",
            str(path),
            "-o",
            str(out),
            "--paths.train",
            str(TRAIN_DIR),
            "--paths.dev",
            str(CORPUS / "en_ewt-ud-dev.spacy"),
        ]
    )


def step_package(force: bool) -> None:
    from services.nlp.lemmatizer import build_lemma_tables
    from services.nlp.pipeline import package_model

    tables = build_lemma_tables([EWT / "en_ewt-ud-train.conllu", DOMAIN / "domain-train.conllu"])
    best = BUILD / "finetuned" / "model-best"
    package_model(best if best.exists() else BUILD / "trained" / "model-best", MODEL_OUT, tables)
    size = sum(p.stat().st_size for p in MODEL_OUT.rglob("*") if p.is_file())
    print(f"wrote {MODEL_OUT} ({size / 1e6:.1f} MB)")
    if size > 30e6:
        raise SystemExit("the packaged pipeline is over 30 MB")


def step_evaluate(force: bool) -> None:
    from services.nlp.pipeline import evaluate_treebank

    scores = {
        "ewt_test": evaluate_treebank(EWT / "en_ewt-ud-test.conllu"),
        "domain_test": evaluate_treebank(DOMAIN / "domain-test.conllu"),
    }
    print(f"{'split':<12} {'pos':>6} {'tag':>6} {'lemma':>6} {'uas':>6} {'las':>6}")
    for split, s in scores.items():
        print(
            f"{split:<12} {s['pos']:6.3f} {s['tag']:6.3f} {s['lemma']:6.3f} {s['uas']:6.3f} {s['las']:6.3f}"
        )
    (MODEL_OUT / "scores.json").write_text(json.dumps(scores, indent=2) + "\n")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", nargs="+", choices=STEPS, default=list(STEPS), help="steps to run, in order")
    ap.add_argument("--force", action="store_true", help="redo steps whose outputs exist")
    args = ap.parse_args(argv)
    for name in STEPS:
        if name in args.steps:
            print(f"== {name}", flush=True)
            globals()[f"step_{name}"](args.force)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
