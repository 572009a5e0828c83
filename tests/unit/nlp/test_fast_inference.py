"""The fast forward passes (FastTok2Vec, MatmulOps) give the trained pipeline's own annotations."""

from __future__ import annotations

import numpy as np
import pytest
import spacy
from thinc.api import NumpyOps

from services.nlp.fast_tok2vec import FastTok2Vec
from services.nlp.matmul_ops import MatmulOps
from services.nlp.pipeline import MODEL_DIR, get_nlp, keep_hyphenated_verbs

SENTENCES = [
    "Eve sits on the chairs and types on the laptop.",
    "A small wooden table stands in the middle of the kitchen, next to the window.",
    "Prof. Kim waves at Tom and says hello.",
    "Tom high-fives Ada.",
    "The next morning, Jack lights a candle and reads a book under which a box lies.",
    "Camera close up on Ada for 3 seconds.",
    "x",
]


@pytest.fixture(scope="module")
def reference():
    """The shipped pipeline as spaCy loads it: thinc's tok2vec forward and blis gemm."""
    nlp = spacy.load(MODEL_DIR, exclude=["senter"])
    keep_hyphenated_verbs(nlp)
    return nlp


def _annotations(doc):
    return [(t.head.i, t.dep_, t.tag_, t.pos_, str(t.morph), t.lemma_, t.is_sent_start) for t in doc]


def test_the_shipped_pipeline_runs_the_fast_forward():
    nlp = get_nlp()
    assert "predict" in nlp.get_pipe("tok2vec").__dict__
    for name in ("tagger", "morphologizer", "parser"):
        assert isinstance(nlp.get_pipe(name).model.ops, MatmulOps)


def test_fast_tok2vec_matches_thincs_forward(reference):
    model = reference.get_pipe("tok2vec").model
    fast = FastTok2Vec.from_model(model)
    assert fast is not None and fast.width == 96
    docs = [reference.make_doc(s) for s in SENTENCES] + [reference.make_doc("")]
    for batch in ([d] for d in docs[:-1]), [docs]:
        for group in batch:
            want, got = model.predict(group), fast(group)
            assert len(want) == len(got)
            for w, g in zip(want, got, strict=True):
                assert w.shape == g.shape
                np.testing.assert_allclose(g, w, rtol=1e-5, atol=1e-4)
    assert [a.shape for a in fast([reference.make_doc("")])] == [(0, 96)]


def test_fast_tok2vec_declines_another_architecture():
    from spacy.util import registry

    embed = registry.architectures.get("spacy.MultiHashEmbed.v2")(
        width=32, attrs=["NORM", "SHAPE"], rows=[100, 50], include_static_vectors=False
    )
    wide = registry.architectures.get("spacy.MaxoutWindowEncoder.v2")(
        width=32, window_size=2, maxout_pieces=3, depth=2
    )
    docs = [spacy.blank("en").make_doc("Ada waves at Tom.")]
    model = registry.architectures.get("spacy.Tok2Vec.v2")(embed, wide)
    model.initialize(X=docs)
    assert FastTok2Vec.from_model(model) is None
    narrow = registry.architectures.get("spacy.MaxoutWindowEncoder.v2")(
        width=32, window_size=1, maxout_pieces=3, depth=2
    )
    embed2 = registry.architectures.get("spacy.MultiHashEmbed.v2")(
        width=32, attrs=["NORM", "SHAPE"], rows=[100, 50], include_static_vectors=False
    )
    same_kind = registry.architectures.get("spacy.Tok2Vec.v2")(embed2, narrow)
    same_kind.initialize(X=docs)
    fast = FastTok2Vec.from_model(same_kind)
    assert fast is not None
    np.testing.assert_allclose(fast(docs)[0], same_kind.predict(docs)[0], rtol=1e-5, atol=1e-4)


def _gold_texts(repo_root):
    out = []
    for split in ("dev", "test", "styles"):
        for line in (
            (repo_root / "eval" / "data" / "nlp" / f"{split}.txt").read_text(encoding="utf-8").splitlines()
        ):
            if line.startswith("T "):
                out.append(line[2:].replace("\\n", "\n"))
    return out


def test_fast_pipeline_annotates_as_the_reference(reference, repo_root):
    nlp = get_nlp()
    for text in SENTENCES:
        assert _annotations(nlp(text)) == _annotations(reference(text)), text
    texts = _gold_texts(repo_root)
    assert len(texts) >= 300
    fast = [_annotations(d) for d in nlp.pipe(texts, batch_size=64)]
    assert fast == [_annotations(d) for d in reference.pipe(texts, batch_size=64)]


@pytest.mark.parametrize("trans1,trans2", [(False, False), (False, True), (True, False), (True, True)])
def test_matmul_ops_gemm_is_blis_gemm(trans1, trans2):
    rng = np.random.default_rng(7)
    x = rng.standard_normal((12, 40) if not trans1 else (40, 12)).astype("float32")
    y = rng.standard_normal((40, 30) if not trans2 else (30, 40)).astype("float32")
    y.flags.writeable = False
    want = NumpyOps().gemm(x, y, trans1=trans1, trans2=trans2)
    got = MatmulOps().gemm(x, y, trans1=trans1, trans2=trans2)
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5)
    out = np.empty_like(want)
    assert MatmulOps().gemm(x, y, out=out, trans1=trans1, trans2=trans2) is out
    np.testing.assert_allclose(out, want, rtol=1e-5, atol=1e-5)


def test_matmul_ops_keeps_one_transposed_copy_per_read_only_weight():
    ops = MatmulOps()
    w = np.arange(12, dtype="float32").reshape(3, 4)
    assert not ops.transposed(w).flags.c_contiguous  # writable: a view, never cached
    w.flags.writeable = False
    first = ops.transposed(w)
    assert first.flags.c_contiguous and np.array_equal(first, w.T)
    assert ops.transposed(w.reshape(3, 4)) is first  # a new view of the same memory hits
    assert ops.transposed(w.reshape(4, 3)) is not first  # another shape is another matrix
