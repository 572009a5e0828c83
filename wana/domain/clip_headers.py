"""Where the action clips live and what a reader of words needs of each (name, synonyms, tags, the object
it touches), read without numpy or keyframes.

The parser needs the clips' words at start-up, long before motion synthesis needs their poses: building
every keyframe (``wana.domain.actions.load_library``) and importing scipy for it costs about 0.6 s, reading
the headers a few milliseconds. Same files and precedence as the library itself.
"""

from __future__ import annotations

import functools
import json
import os
from dataclasses import dataclass
from pathlib import Path

from wana.domain.paths import asset_path

ACTIONS_DIR = asset_path("actions")
IMPORTED_DIR = ACTIONS_DIR / "imported"


@dataclass(frozen=True)
class ClipHeader:
    """A clip's words: its name, synonyms, tags and the object its interaction touches ("" for none)."""

    name: str
    synonyms: tuple[str, ...]
    tags: tuple[str, ...]
    interaction_object: str


def library_dirs() -> list[Path]:
    """The clip folders in order of precedence (authored, imported, then $WANA_ACTIONS_DIR; later wins)."""
    return list(library_key())


def library_key() -> tuple[Path, ...]:
    """``library_dirs`` as the tuple the caches are keyed by (get_clip asks for it on every clip it looks up:
    the paths are built once per value of $WANA_ACTIONS_DIR)."""
    return _dirs(os.environ.get("WANA_ACTIONS_DIR") or "")


@functools.lru_cache(maxsize=8)
def _dirs(extra: str) -> tuple[Path, ...]:
    return (ACTIONS_DIR, IMPORTED_DIR, Path(extra)) if extra else (ACTIONS_DIR, IMPORTED_DIR)


def clip_files(dirs: tuple[Path, ...]) -> list[tuple[Path, Path]]:
    """(folder, clip file) in load order; files starting with "_" are not clips."""
    return [
        (directory, path)
        for directory in dirs
        if directory.is_dir()
        for path in sorted(directory.glob("*.json"))
        if not path.name.startswith("_")
    ]


def clip_headers() -> dict[str, ClipHeader]:
    """Every clip's header by name, cached per set of folders (``cache_clear`` after an import)."""
    return dict(_headers(tuple(library_dirs())))


@functools.lru_cache(maxsize=4)
def _headers(dirs: tuple[Path, ...]) -> dict[str, ClipHeader]:
    headers: dict[str, ClipHeader] = {}
    for _, path in clip_files(dirs):
        d = json.loads(path.read_text())
        inter = d.get("interaction") or {}
        header = ClipHeader(
            name=str(d["name"]),
            synonyms=tuple(d.get("synonyms", ())),
            tags=tuple(d.get("tags", ())),
            interaction_object=str(inter.get("object", "")),
        )
        headers[header.name] = header
    return headers


clip_headers.cache_clear = _headers.cache_clear  # type: ignore[attr-defined]
