"""`wana animate --cast NAME=FILE [--cast-map [NAME=]FILE]`: the user's characters, read and checked before
the pipeline runs (a missing file or a rig the map cannot cover stops at once), and their names checked
against the story's characters after it (an unknown name gets a "did you mean")."""

from __future__ import annotations

import difflib
import json
from collections.abc import Iterable, Sequence
from pathlib import Path

from proto.render import CastMember
from wana.cast import CastError, map_joints, read_rig
from wana.cast.fbx import fbx_to_glb

SUFFIXES = (".glb", ".vrm", ".fbx")


def _pair(value: str, what: str) -> tuple[str, str]:
    name, sep, path = value.partition("=")
    if not sep or not name.strip() or not path.strip():
        raise CastError(f"{what} takes NAME=FILE, got {value!r}")
    return name.strip(), path.strip()


def _read_map(path: str) -> dict[str, str]:
    p = Path(path)
    if not p.is_file():
        raise CastError(f"no such joint map file: {path}")
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise CastError(f"the joint map {path} is not JSON: {exc}") from exc
    if not isinstance(data, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in data.items()
    ):
        raise CastError(f"the joint map {path} must be one JSON object: canonical joint -> your joint name")
    return data


def load_cast(specs: Sequence[str], maps: Sequence[str] = ()) -> list[CastMember]:
    """The ``--cast`` characters as messages for the render service, each read and its joints mapped.

    Args:
        specs: "NAME=FILE" (.glb, .vrm, or .fbx through Blender).
        maps: "FILE" (for every cast character) or "NAME=FILE": canonical joint -> the rig's joint name.

    Raises:
        CastError: a message for the user.
    """
    shared: dict[str, str] = {}
    per_name: dict[str, dict[str, str]] = {}
    for m in maps:
        name, sep, path = m.partition("=")
        if sep and not Path(m).is_file():
            per_name[name.strip()] = _read_map(path.strip())
        else:
            shared = _read_map(m)
    members = []
    seen: set[str] = set()
    for spec in specs:
        name, path = _pair(spec, "--cast")
        if name in seen:
            raise CastError(f"--cast names {name} twice")
        seen.add(name)
        p = Path(path)
        if not p.is_file():
            raise CastError(f"no such character file for {name}: {path}")
        suffix = p.suffix.lower()
        if suffix not in SUFFIXES:
            raise CastError(f"{path}: a character must be one of {', '.join(SUFFIXES)}")
        data = fbx_to_glb(p) if suffix == ".fbx" else p.read_bytes()
        joint_map = {**shared, **per_name.get(name, {})}
        label = f"{path} (for {name})"
        map_joints(read_rig(data, label), joint_map or None, label)
        members.append(CastMember(name=name, glb=data, joint_map=joint_map))
    unknown = set(per_name) - seen
    if unknown:
        raise CastError(f"--cast-map names {', '.join(sorted(unknown))}, not given with --cast")
    return members


def unknown_names(members: Iterable[CastMember], characters: Sequence[str]) -> list[str]:
    """One message per cast name the story has no character for, with the nearest story name."""
    out = []
    for m in members:
        if m.name in characters:
            continue
        near = difflib.get_close_matches(m.name, list(characters), n=1, cutoff=0.5)
        hint = f"; did you mean {near[0]}?" if near else f"; the story's characters: {', '.join(characters)}"
        out.append(f"--cast {m.name}: the story has no character {m.name}{hint}")
    return out
