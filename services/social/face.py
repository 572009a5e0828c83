"""The linear VAD -> face model: blendshape weights = clip(B @ (valence, arousal, dominance), 0, 1).

B (E x 3) follows the FACS reading of the affect dimensions (Russell's circumplex and Mehrabian's PAD):
positive valence raises the lip corners (smile) and negative valence lowers them (frown); arousal opens the
mouth and lifts the brows, low arousal closes the eyes; dominance lowers and knits the brows (anger,
contempt) while low dominance lifts them (surprise, fear) and pouts (pucker). A neutral emotion (0, 0, 0)
is the neutral face (all weights 0). Rows are in ``wana.assets.characters.EXPRESSIONS`` order.
"""

from __future__ import annotations

import numpy as np

from wana.assets.characters import EXPRESSIONS

#                      valence arousal dominance
_ROWS: dict[str, tuple[float, float, float]] = {
    "smile": (0.95, 0.10, 0.10),
    "frown": (-0.85, 0.10, -0.10),
    "brows_up": (0.05, 0.55, -0.55),
    "brows_down": (-0.45, 0.30, 0.50),
    "mouth_open": (0.00, 0.70, 0.00),
    "eyes_closed": (-0.10, -0.65, 0.00),
    "squint": (-0.25, 0.20, 0.40),
    "pucker": (-0.20, -0.15, -0.40),
}
FACE_MATRIX: np.ndarray = np.array(
    [_ROWS.get(name, (0.0, 0.0, 0.0)) for name in EXPRESSIONS], dtype=np.float32
)
"""(E, 3) float32: one row per face blendshape in EXPRESSIONS order."""


def face_weights(vad: tuple[float, float, float] | np.ndarray) -> np.ndarray:
    """Blendshape weights of an emotion.

    Args:
        vad: (3,) or (N, 3) valence, arousal, dominance in [-1, 1].

    Returns:
        (E,) or (N, E) float32 weights in [0, 1].
    """
    v = np.asarray(vad, dtype=np.float32)
    if v.shape[-1] != 3:
        raise ValueError(f"a VAD vector has 3 values, got shape {v.shape}")
    return np.clip(v @ FACE_MATRIX.T, 0.0, 1.0).astype(np.float32)


def expression_names() -> list[str]:
    return list(EXPRESSIONS)
