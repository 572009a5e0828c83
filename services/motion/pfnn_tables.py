"""Run the phase-binned PFNN rollout (pfnn_fast.onnx) in numpy, frame by frame, with no weight copies.

pfnn_fast.onnx (services.motion.pfnn_onnx) holds, per layer, a table of phase-blended weights
(bins, n_in, n_out). onnxruntime executes the graph by Gathering one bin's weights per layer and
frame, which copies ~300 kB per frame: half of its time. This executor reads the same tables out
of the ONNX file and runs the same arithmetic (float32 weights, ELU, pose feedback, phase kept in
bin units) on numpy views of the tables, so a frame costs three matrix-vector products and a few
small ufuncs. onnxruntime stays the reference: tests/unit/motion/test_fast_paths.py checks that
both give the same outputs.

The rollout buffer has one row per frame: [control (60), 1, previous output (N_OUT + 1)], so the
input of frame k is the contiguous slice row[k, :61 + N_POSE] and the output of frame k is written
straight into row k + 1 (its first N_POSE values are the next frame's pose input).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from services.motion.pfnn_layout import N_OUT, N_POSE

N_CONTROL = 60
N_HEAD = N_CONTROL + 1  # control and the constant 1 (bias row)


def load_phase_tables(path: Path) -> list[np.ndarray]:
    """The three phase tables of a pfnn_fast.onnx, float32.

    Returns:
        [W0 (bins, 61 + N_POSE, h + 1), W1 (bins, h + 1, h + 1), W2 (bins, h + 1, N_OUT + 1)].

    Raises:
        ValueError: the file is no phase-binned rollout graph.
    """
    import onnx
    from onnx import numpy_helper

    model = onnx.load(str(path))
    inits = {i.name: i for i in model.graph.initializer}
    try:
        tables = [numpy_helper.to_array(inits[f"W{i}_half"]).astype(np.float32) for i in range(3)]
    except KeyError as exc:
        raise ValueError(f"{path} holds no phase tables W0_half..W2_half") from exc
    w0, w1, w2 = tables
    if w0.shape[1] != N_HEAD + N_POSE or w2.shape[2] != N_OUT + 1 or w0.shape[0] != w2.shape[0]:
        raise ValueError(f"{path}: phase tables of unexpected shapes {[t.shape for t in tables]}")
    return [np.ascontiguousarray(t) for t in tables]


class PhaseTableRuntime:
    """The PFNN rollout on the phase tables of pfnn_fast.onnx, in numpy (single-threaded BLAS calls)."""

    kind = "numpy"

    def __init__(self, path: Path) -> None:
        self.w0, self.w1, self.w2 = load_phase_tables(path)
        self.bins = int(self.w0.shape[0])
        self.hidden = int(self.w1.shape[1])
        # Per-bin views, made once: indexing a Python list is cheaper than a numpy index per frame.
        self._w0 = list(self.w0)
        self._w1 = list(self.w1)
        self._w2 = list(self.w2)

    def run(self, control: np.ndarray, pose0: np.ndarray, phase0: float) -> np.ndarray:
        """Y (T, N_OUT) float32 for control (T, 60), starting from pose0 (N_POSE,) at phase0 in cycles."""
        t = len(control)
        width = N_HEAD + N_OUT + 1
        rows = np.empty((t + 1, width), np.float32)
        rows[:t, :N_CONTROL] = control
        rows[:, N_CONTROL] = 1.0
        rows[0, N_HEAD : N_HEAD + N_POSE] = np.asarray(pose0, np.float32).reshape(N_POSE)
        n_in = N_HEAD + N_POSE
        z = np.empty(self.hidden, np.float32)
        neg = np.empty(self.hidden, np.float32)
        h = np.empty(self.hidden, np.float32)
        w0, w1, w2 = self._w0, self._w1, self._w2
        dot, minimum, maximum, expm1 = np.dot, np.minimum, np.maximum, np.expm1
        bins = self.bins
        top = 0.5 * bins
        dphase_col = N_HEAD + N_OUT
        phase = (float(phase0) % 1.0) * bins  # in bins, [0, bins)
        for k in range(t):
            b = int(phase)
            dot(rows[k, :n_in], w0[b], out=z)
            minimum(z, 0.0, out=neg)  # ELU(z) = max(z, expm1(min(z, 0)))
            expm1(neg, out=neg)
            maximum(z, neg, out=h)
            dot(h, w1[b], out=z)
            minimum(z, 0.0, out=neg)
            expm1(neg, out=neg)
            maximum(z, neg, out=h)
            out = rows[k + 1, N_HEAD:]
            dot(h, w2[b], out=out)
            d = float(out[N_OUT])
            phase = (phase + (0.0 if d < 0.0 else top if d > top else d)) % bins
            if phase >= bins:  # float rounding of the modulo
                phase = 0.0
        return rows[1:, N_HEAD:dphase_col]
