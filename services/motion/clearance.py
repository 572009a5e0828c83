"""What the clearance passes share (arm_clearance, trunk_clearance): the room's furniture as the story checks
see it, the deepest body sphere inside it per frame, what a character sits or lies on, and how a per-frame
correction is held and eased over the frames around it."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Scene
from wana.domain.skeleton import REST_OFFSETS
from wana.fidelity.body_checks import is_soft, visible_depth
from wana.fidelity.solids import depth_inside
from wana.fidelity.world import World

SEATED_HIPS = 0.8  # share of the standing hips height below which hips over a seat or bed sit or lie on it
CLEAR_M = 0.015  # metres a corrected sphere is left short of where it would look inside
HOLD = 4  # frames a correction is held on either side of the frames that need it ...
EASE = 4  # ... and then eased out over (a triangle of this half-width)


def furniture(
    scene: Scene, ignore: frozenset[str] = frozenset()
) -> list[tuple[PlacedObject, np.ndarray, float]]:
    """(object, its world box (2, 3), the extra depth a cushion gives) for every piece of furniture an arm can
    go into, as the story checks see the room."""
    return [
        (o, outer, 0.05 if is_soft(o.category, dict(o.attributes)) else 0.0)
        for o, _, outer in World(scene).solids
        if o.id not in ignore
    ]


def deepest(
    centres: np.ndarray,
    radii: np.ndarray,
    solids: list[tuple[PlacedObject, np.ndarray, float]],
    skip: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per frame, how far past its allowance the worst sphere is (T,), that sphere (T,) and the index of
    its object in ``solids`` (T,; -1 where it is clear); ``skip`` (T, len(solids)) bool: objects not in
    the way on a frame."""
    t, p = centres.shape[:2]
    excess = np.zeros((t, p))
    owner = np.full((t, p), -1)
    allowance = visible_depth(radii) - CLEAR_M
    for k, (placed, outer, soft) in enumerate(solids):
        near = np.all(
            (centres >= outer[0] - radii[None, :, None]) & (centres <= outer[1] + radii[None, :, None]), 2
        )
        if skip is not None:
            near &= ~skip[:, k, None]
        if not near.any():
            continue
        ti, pi = np.nonzero(near)
        over = depth_inside(placed, centres[ti, pi], radii[pi]) - allowance[pi] - soft
        worse = over > excess[ti, pi]
        excess[ti[worse], pi[worse]] = over[worse]
        owner[ti[worse], pi[worse]] = k
    worst = np.argmax(excess, axis=1)
    frames = np.arange(t)
    return excess[frames, worst], worst, owner[frames, worst]


def _filtered(signal: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """(T,) the signal convolved with an odd-length kernel, zero beyond its ends (any T, shorter than the
    kernel too)."""
    half = len(kernel) // 2
    return np.convolve(np.pad(signal, half), kernel, mode="valid")


def _edge_weight(t: int) -> np.ndarray:
    """(T,) 0 on a piece's first and last frame, 1 from EASE frames in: the piece before or after was cleared
    on its own, so a correction comes in and goes out inside the piece instead of jumping at its ends."""
    frames = np.arange(t, dtype=float)
    return np.clip(np.minimum(frames, t - 1 - frames) / EASE, 0.0, 1.0)


def spread_turns(turn: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """(T, 3) rotation vectors held HOLD frames around each correction (the largest wins), eased over EASE,
    and faded to none near the frames in ``keep`` (T,) bool."""
    t = len(turn)
    size = np.linalg.norm(turn, axis=1)
    held = turn.copy()
    best = size.copy()
    for d in range(1, min(HOLD, t - 1) + 1):
        for src, dst in ((slice(0, t - d), slice(d, t)), (slice(d, t), slice(0, t - d))):
            bigger = size[src] > best[dst]
            held[dst][bigger] = turn[src][bigger]
            best[dst][bigger] = size[src][bigger]
    kernel = np.r_[np.arange(1, EASE + 2), np.arange(EASE, 0, -1)].astype(float)
    kernel /= kernel.max()
    eased = np.stack([_filtered(held[:, i], kernel / kernel.sum()) for i in range(3)], 1)
    # the average of a held plateau is its peak: the correction is whole there and eases off at its edges
    if keep.any():
        near = _filtered(keep.astype(float), np.ones(2 * EASE + 1)) > 0
        fade = 1.0 - _filtered(near.astype(float), kernel / kernel.sum())
        eased *= np.clip(fade, 0.0, 1.0)[:, None]
    return eased * _edge_weight(t)[:, None]


def seated_on(root: np.ndarray, solids: list[tuple[PlacedObject, np.ndarray, float]]) -> np.ndarray:
    """(T, len(solids)) bool: the objects a character sits or lies on, frame by frame (hips over the object's
    box and lower than standing): the stated contact, which the checks let the whole body touch."""
    low = root[:, 1] < SEATED_HIPS * REST_OFFSETS[0, 1]
    out = np.zeros((len(root), len(solids)), bool)
    for k, (_, outer, _) in enumerate(solids):
        over = np.all((root[:, [0, 2]] >= outer[0, [0, 2]]) & (root[:, [0, 2]] <= outer[1, [0, 2]]), axis=1)
        out[:, k] = low & over
    return out


__all__ = ["CLEAR_M", "deepest", "furniture", "seated_on", "spread_turns"]
