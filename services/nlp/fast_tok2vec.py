"""The shipped tok2vec's forward pass for inference, in a dozen array calls instead of ~60 layer calls.

The trained pipeline's tok2vec is spaCy's ``MultiHashEmbed.v2`` (NORM, PREFIX, SUFFIX, SHAPE hash
embeddings, mixed by a maxout + layer norm) followed by ``MaxoutWindowEncoder.v2`` (residual window-1
maxout + layer norm blocks over the documents flattened with zero padding between them). thinc runs
it as a tree of small layers; on a sentence of ten tokens the dispatch (chain, with_array, flatten,
ragged conversions, residual, concatenate) costs about as much as the matrix products.
:class:`FastTok2Vec` reads the same weights and runs the same operations in the same order (thinc's
``maxout``, ``seq2col``, ``hash``, ``gather_add``; the layer norm as thinc writes it), with one
change: the products go through numpy's OpenBLAS against a contiguous ``W.T`` made once, several
times faster than thinc's blis ``gemm`` here. The vectors equal thinc's up to float32 rounding and
every annotation of the gold sentences is the same (``tests/unit/nlp/test_fast_inference.py``). It is built only when the model has exactly that
structure; anything else keeps thinc's forward.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from spacy.tokens import Doc
from thinc.api import Model


@dataclass(frozen=True)
class _Maxout:
    Wt: np.ndarray  # (nI, nO * nP), contiguous: the layer's W viewed 2-D and transposed once
    b: np.ndarray  # (nO * nP,)
    nO: int
    nP: int
    G: np.ndarray  # layer norm scale
    beta: np.ndarray  # layer norm shift


def _maxout_ln(ops: Any, layer: _Maxout, X: np.ndarray) -> np.ndarray:
    """thinc's ``maxout >> layernorm`` at inference (dropout is the identity)."""
    Y = X @ layer.Wt  # numpy's BLAS: ~5x faster than thinc's blis gemm on these small products
    Y += layer.b
    best, _ = ops.maxout(Y.reshape((Y.shape[0], layer.nO, layer.nP)))
    mu = best.mean(axis=1, keepdims=True)
    centred = best - mu
    var = np.multiply(centred, centred).mean(axis=1, keepdims=True)  # what ndarray.var computes
    var += 1e-08
    out = centred * var ** (-1.0 / 2.0)
    out *= layer.G
    out += layer.beta
    return out  # type: ignore[no-any-return]


class FastTok2Vec:
    """Inference-only forward of a MultiHashEmbed + MaxoutWindowEncoder tok2vec model."""

    def __init__(
        self,
        ops: Any,
        columns: list[Any],
        tables: list[tuple[np.ndarray, int]],
        mixer: _Maxout,
        blocks: list[_Maxout],
        pad: int,
    ) -> None:
        self.ops = ops
        self.columns = columns
        self.tables = tables  # (E, seed) per column
        self.mixer = mixer
        self.blocks = blocks
        self.pad = pad
        self.width = mixer.nO

    @classmethod
    def from_model(cls, model: Model) -> FastTok2Vec | None:  # type: ignore[type-arg]
        """The fast forward of ``model``, or None when its structure is not the one this implements."""
        nodes = list(model.walk())
        names = [n.name for n in nodes]
        extract = [n for n in nodes if n.name == "extract_features"]
        embeds = [n for n in nodes if n.name == "hashembed"]
        maxouts = [n for n in nodes if n.name == "maxout"]
        norms = [n for n in nodes if n.name == "layernorm"]
        windows = [n for n in nodes if n.name == "expand_window"]
        residuals = [n for n in nodes if n.name.startswith("residual(") and len(n.layers) == 1]
        arrays = [n for n in nodes if n.name.startswith("with_array(residual(")]
        depth = len(residuals)
        leaves = {n.name for n in nodes if not n.layers}
        expected_leaves = {
            "extract_features",
            "list2ragged",
            "ints-getitem",
            "hashembed",
            "maxout",
            "layernorm",
            "dropout",
            "ragged2list",
            "expand_window",
        }
        if (
            len(extract) != 1
            or leaves != expected_leaves
            or len(embeds) != len(extract[0].attrs["columns"])
            or depth < 1
            or len(maxouts) != depth + 1
            or len(norms) != depth + 1
            or len(windows) != depth
            or any(w.attrs.get("window_size") != 1 for w in windows)
            or len(arrays) != 1
            or names.count("ragged2list") != 1
        ):
            return None
        ops = model.ops

        def maxout(i: int) -> _Maxout:
            m, ln = maxouts[i], norms[i]
            nO, nP, nI = (m.get_dim(d) for d in ("nO", "nP", "nI"))
            return _Maxout(
                Wt=np.ascontiguousarray(ops.reshape2f(m.get_param("W"), nO * nP, nI).T),
                b=np.asarray(ops.reshape1f(m.get_param("b"), nO * nP)),
                nO=nO,
                nP=nP,
                G=np.asarray(ln.get_param("G")),
                beta=np.asarray(ln.get_param("b")),
            )

        tables = [(np.asarray(e.get_param("E")), int(e.attrs["seed"])) for e in embeds]
        if [e.attrs.get("column") for e in embeds] != list(range(len(embeds))):
            return None
        return cls(
            ops,
            list(extract[0].attrs["columns"]),
            tables,
            maxout(0),
            [maxout(i) for i in range(1, depth + 1)],
            int(arrays[0].attrs["pad"]),
        )

    def embed(self, docs: Sequence[Doc]) -> np.ndarray:
        """The documents' token embeddings (MultiHashEmbed), all docs' tokens in one array."""
        ops = self.ops
        feats = np.concatenate([ops.asarray2i(doc.to_array(self.columns), dtype="uint64") for doc in docs])
        parts = []
        for i, (E, seed) in enumerate(self.tables):
            ids = ops.as_contig(feats[:, i], dtype="uint64")
            parts.append(ops.gather_add(E, ops.hash(ids, seed) % E.shape[0]))
        return _maxout_ln(ops, self.mixer, np.hstack(parts))

    def __call__(self, docs: Sequence[Doc]) -> list[np.ndarray]:
        """Token vectors per document, as ``tok2vec.model.predict(docs)`` returns them."""
        ops = self.ops
        lengths = [len(doc) for doc in docs]
        if not any(lengths):
            return [ops.alloc2f(0, self.width) for _ in docs]
        pad = self.pad
        embedded = self.embed([doc for doc in docs if len(doc)])
        zeros = np.zeros((pad, self.width), dtype=embedded.dtype)
        pieces: list[np.ndarray] = [zeros]
        start = 0
        for n in lengths:
            if n:
                pieces += [embedded[start : start + n], zeros]
                start += n
        X = np.concatenate(pieces)
        for block in self.blocks:
            X = X + _maxout_ln(ops, block, ops.seq2col(X, 1))
        out: list[np.ndarray] = []
        start = pad
        for n in lengths:
            out.append(X[start : start + n])
            if n:
                start += n + pad
        return out
