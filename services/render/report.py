"""report.json: what the pipeline understood and chose (SSG, retrieval, costs, diagnostics) plus what
the render stage produced (frames, commands on frames, captions, files)."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import msgspec
import numpy as np


def to_jsonable(value: Any) -> Any:
    """msgspec structs, numpy arrays/scalars, paths, bytes, sets and tuples -> plain JSON values."""
    if isinstance(value, msgspec.Struct):
        return to_jsonable(msgspec.to_builtins(value))
    if isinstance(value, np.ndarray):
        return to_jsonable(value.tolist())
    if isinstance(value, np.generic):
        return to_jsonable(value.item())
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set, frozenset)):
        return [to_jsonable(v) for v in value]
    if isinstance(value, Path):
        return str(value)
    if isinstance(value, (bytes, bytearray)):
        return f"<{len(value)} bytes>"
    if value is None or isinstance(value, (str, int, bool)):
        return value
    if hasattr(value, "__dict__"):
        return to_jsonable(vars(value))
    return str(value)


def build_report(report: Mapping[str, Any] | None, render: Mapping[str, Any]) -> dict[str, Any]:
    """The pipeline's report (kept as given) with a "render" section added."""
    out = dict(to_jsonable(report or {}))
    out["render"] = to_jsonable(render)
    return out


def write_report(path: str | Path, report: Mapping[str, Any] | None, render: Mapping[str, Any]) -> Path:
    """Write report.json (UTF-8, indented) and return its path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(build_report(report, render), indent=2, ensure_ascii=False))
    return p
