"""The trained spaCy pipeline: lazy cached loading, packaging after training, treebank evaluation.

The pipeline (``models/nlp/en_wana``) is trained by ``scripts/train_nlp.py``: tok2vec (CNN), tagger
(XPOS), morphologizer (UPOS + features), dependency parser, wana's lookup lemmatizer; senter ships
disabled because the parser already sets sentence boundaries. :func:`get_nlp` switches the loaded
pipeline to the fast inference forward (:func:`use_fast_inference`): same annotations, less CPU.
"""

from __future__ import annotations

import threading
from pathlib import Path

import spacy
from spacy.language import Language

from services.nlp import lemmatizer as _lemmatizer  # noqa: F401 - registers the "wana_lemmatizer" factory
from wana.domain.paths import model_path

MODEL_DIR = model_path("nlp", "en_wana")
MODEL_VERSION = "0.1.0"

_lock = threading.Lock()
_nlp: Language | None = None


class ModelMissing(RuntimeError):
    """Raised when the trained pipeline is not where it should be."""


def get_nlp() -> Language:
    """The process-wide pipeline, loaded on first use (thread-safe)."""
    global _nlp
    if _nlp is None:
        with _lock:
            if _nlp is None:
                if not (MODEL_DIR / "config.cfg").exists():
                    raise ModelMissing(f"no trained pipeline at {MODEL_DIR}; run scripts/train_nlp.py")
                nlp = spacy.load(MODEL_DIR, exclude=["senter"])
                keep_hyphenated_verbs(nlp)
                use_fast_inference(nlp)
                _nlp = nlp
    return _nlp


def use_fast_inference(nlp: Language, on: bool = True) -> bool:
    """Run the pipeline's forward passes the fast way: the tok2vec through :class:`FastTok2Vec` and
    every matrix product through :class:`MatmulOps` (numpy's BLAS, pre-transposed weights). The
    annotations are the same (``tests/unit/nlp/test_fast_inference.py``); about 1 ms less CPU per
    sentence, a third of the parse (``bench/nlp.py --alternate``). ``on=False`` restores thinc's forward and ops (the
    reference the benchmark alternates with). Returns whether the fast tok2vec is in use.
    """
    from thinc.api import Model, NumpyOps

    from services.nlp.fast_tok2vec import FastTok2Vec
    from services.nlp.matmul_ops import use_matmul_ops

    if on:
        use_matmul_ops(nlp)
    else:
        ops = NumpyOps()
        for _, pipe in nlp.pipeline:
            if isinstance(getattr(pipe, "model", None), Model):
                for node in pipe.model.walk():  # type: ignore[attr-defined]
                    node.ops = ops
    tok2vec = nlp.get_pipe("tok2vec")
    tok2vec.__dict__.pop("predict", None)  # the class's predict (thinc) again
    fast = FastTok2Vec.from_model(tok2vec.model) if on else None  # type: ignore[attr-defined]
    if fast is None:
        return False
    tok2vec.predict = lambda docs: fast(list(docs))  # type: ignore[attr-defined]
    return True


def _inflections(base: str) -> list[str]:
    stem = base[:-1] if base.endswith("e") else base
    return [base, base + "s", stem + "ed", stem + "ing"]


def keep_hyphenated_verbs(nlp: Language) -> None:
    """Keep hyphenated action verbs ("high-fives") one token, as the tagger knows "highfives" a verb.

    spaCy's English infixes split every hyphen ("high - fives"), which the parser reads as an adjective
    and a number; a tokenizer special case per inflected (and capitalised) form keeps the word whole.
    """
    from spacy.symbols import ORTH

    from services.nlp.lexicon import hyphenated_verbs

    for base in sorted(hyphenated_verbs()):
        for form in _inflections(base):
            for variant in (form, form.capitalize()):
                nlp.tokenizer.add_special_case(variant, [{ORTH: variant}])  # type: ignore[union-attr]


def package_model(trained_dir: Path, out_dir: Path, tables: _lemmatizer.LemmaTables) -> None:
    """Load spaCy's ``model-best``, add the lookup lemmatizer, disable senter and write ``out_dir``."""
    import shutil

    nlp = spacy.load(trained_dir)
    lem = nlp.add_pipe("wana_lemmatizer", after="morphologizer")
    lem.tables = tables  # type: ignore[attr-defined]
    if "senter" in nlp.pipe_names:
        nlp.disable_pipe("senter")
    nlp.meta.update(
        name="wana",
        version=MODEL_VERSION,
        description="wana English pipeline: UD English-EWT v2.16 + wana domain treebank",
        license="CC BY-SA 4.0 (trained on UD English-EWT)",
        sources=[
            {
                "name": "UD English-EWT",
                "url": "https://github.com/UniversalDependencies/UD_English-EWT",
                "license": "CC BY-SA 4.0",
            }
        ],
    )
    for key in ("train", "dev"):  # no paths of the machine that trained it
        nlp.config["paths"][key] = None
    if out_dir.exists():
        shutil.rmtree(out_dir)
    nlp.to_disk(out_dir)


def evaluate_treebank(conllu: Path, nlp: Language | None = None, limit: int = 0) -> dict[str, float]:
    """POS, XPOS, lemma accuracy and UAS/LAS of the pipeline on a CoNLL-U file.

    Raw sentence text goes through the pipeline's own tokenizer (as users' text does); scores are
    aligned to the gold tokens by spaCy's scorer. Punctuation is excluded from UAS/LAS as spaCy does.

    Args:
        conllu: path of a CoNLL-U file.
        nlp: pipeline to score (default: the shipped one).
        limit: score only the first ``limit`` sentences (0 = all).
    """
    from spacy.training import Example
    from spacy.training.converters import conllu_to_docs

    nlp = nlp or get_nlp()
    text = conllu.read_text(encoding="utf-8")
    gold_docs = list(conllu_to_docs(text, n_sents=1, no_print=True))
    if limit:
        gold_docs = gold_docs[:limit]
    examples = [Example(nlp.make_doc(g.text), g) for g in gold_docs]
    preds = list(nlp.pipe([e.predicted for e in examples], batch_size=256))
    examples = [Example(p, e.reference) for p, e in zip(preds, examples, strict=True)]
    from spacy.scorer import Scorer

    scores: dict[str, float] = {}
    scores.update(Scorer.score_token_attr(examples, "pos"))
    scores.update(Scorer.score_token_attr(examples, "tag"))
    scores.update(Scorer.score_token_attr(examples, "lemma"))
    scores.update(
        Scorer.score_deps(
            examples, "dep", getter=lambda t, a: getattr(t, a + "_").lower(), ignore_labels=("p", "punct")
        )
    )
    return {
        "pos": float(scores["pos_acc"]),
        "tag": float(scores["tag_acc"]),
        "lemma": float(scores["lemma_acc"]),
        "uas": float(scores["dep_uas"]),
        "las": float(scores["dep_las"]),
        "sentences": float(len(examples)),
    }
