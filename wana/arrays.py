"""numpy <-> proto.common.NDArray conversion (proto itself must not import numpy)."""

from __future__ import annotations

import math

import numpy as np

from proto.common import NDArray


def to_wire(array: np.ndarray) -> NDArray:
    """Pack an array as little-endian C-order bytes with its dtype and shape."""
    a = np.ascontiguousarray(array)
    if a.dtype.byteorder == ">":
        a = a.astype(a.dtype.newbyteorder("<"))
    return NDArray(dtype=a.dtype.str, shape=list(a.shape), data=a.tobytes())


def from_wire(wire: NDArray) -> np.ndarray:
    """Unpack an NDArray; raises ValueError when the byte count does not match the shape."""
    dtype = np.dtype(wire.dtype)
    expected = math.prod(wire.shape) * dtype.itemsize  # (not np.prod: called for every piece of every motion)
    if len(wire.data) != expected:
        raise ValueError(
            f"NDArray of shape {wire.shape} {wire.dtype} needs {expected} bytes, got {len(wire.data)}"
        )
    return np.frombuffer(wire.data, dtype=dtype).reshape(wire.shape).copy()
