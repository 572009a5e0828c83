"""thinc's NumpyOps with matrix products through numpy's OpenBLAS against pre-transposed weights.

thinc's layers multiply by a weight matrix transposed on the fly (``gemm(X, W, trans2=True)``). On a
sentence of ten tokens thinc's blis ``gemm`` takes several times as long as numpy's OpenBLAS against a
contiguous copy of ``W.T`` (the parser's 128 x 2048 feature matrix, the taggers' softmax);
:class:`MatmulOps` keeps that copy per weight array (``bench/nlp.py --alternate`` times the pipeline
with and without it). Products agree up to float32 rounding (``tests/unit/nlp/test_fast_inference.py``).
Only read-only arrays are cached (:func:`freeze_params` makes a loaded pipeline's weights read-only,
so an in-place update, as training does, fails loudly instead of meeting a stale copy).
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np
from spacy.language import Language
from thinc.api import Model, NumpyOps


class MatmulOps(NumpyOps):
    """NumpyOps whose ``gemm`` is ``numpy.matmul`` (float32; the same results up to rounding)."""

    name = "numpy"

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._transposed: dict[
            tuple[int, tuple[int, ...], tuple[int, ...]], tuple[np.ndarray, np.ndarray]
        ] = {}
        self._lock = threading.Lock()

    def transposed(self, y: np.ndarray) -> np.ndarray:
        """``y.T`` as a contiguous array: made once for a read-only ``y``, every call otherwise."""
        if y.flags.writeable:
            return y.T
        key = (y.__array_interface__["data"][0], y.shape, y.strides)
        hit = self._transposed.get(key)
        if hit is None:
            hit = (y, np.ascontiguousarray(y.T))  # y kept: its memory cannot be reused under the key
            with self._lock:
                self._transposed[key] = hit
        return hit[1]

    def gemm(
        self,
        x: np.ndarray,
        y: np.ndarray,
        out: np.ndarray | None = None,
        trans1: bool = False,
        trans2: bool = False,
    ) -> np.ndarray:
        a = x.T if trans1 else x
        b = self.transposed(y) if trans2 else y
        if out is None:
            return np.matmul(a, b)  # type: ignore[no-any-return]
        np.matmul(a, b, out=out)
        return out


def freeze_params(model: Model) -> None:  # type: ignore[type-arg]
    """Make the weight matrices ("W") of ``model`` read-only: inference only from here on. (Hash
    embedding tables stay writable: thinc's ``gather_add`` takes only writable arrays; they never
    meet ``gemm``.)"""
    for node in model.walk():
        if "W" in node.param_names and node.has_param("W"):
            node.get_param("W").flags.writeable = False


def use_matmul_ops(nlp: Language) -> MatmulOps:
    """Freeze the trained components' weights and run their products through :class:`MatmulOps`."""
    ops = MatmulOps()
    for _, pipe in nlp.pipeline:
        model = getattr(pipe, "model", None)
        if isinstance(model, Model):
            freeze_params(model)
            for node in model.walk():
                node.ops = ops
    return ops
