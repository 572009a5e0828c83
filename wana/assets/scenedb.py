"""The scene database: generated scenes committed as JSON under assets/scenedb/, loaded fast.

Rebuild (deterministic; seeds are recorded in each record):

    .venv/bin/python -m wana.assets.scenedb --per-room 10

Every stored scene passed ``validate.scene_problems`` when it was written; scenes that fail are
regenerated with the next seed, so the database holds only valid scenes.
"""

from __future__ import annotations

import argparse
import sys
from functools import lru_cache
from pathlib import Path

import msgspec

from proto.scene import Scene
from proto.ssg import ObjectNode, RelationNode
from wana.domain.paths import asset_path

SCENEDB_PATH = asset_path("scenedb", "scenes.json")
GRAMMAR_VERSION = "scene-grammar-v1"


class SceneRecord(msgspec.Struct, frozen=True, kw_only=True):
    """One database scene: its SSG (objects + relations) and the placements realising it."""

    id: str  # e.g. "office-003"
    room_type: str
    objects: list[ObjectNode]
    relations: list[RelationNode]
    scene: Scene
    seed: int = 0  # grammar seed that produced it


class SceneDB(msgspec.Struct, frozen=True, kw_only=True):
    version: str
    command: str
    records: list[SceneRecord]


def load_scenedb(path: str | Path | None = None) -> list[SceneRecord]:
    """All scene records (cached per path).

    Raises:
        FileNotFoundError: when the database file is missing (rebuild it, see the module docstring).
    """
    return list(_load(str(path or SCENEDB_PATH)))


@lru_cache(maxsize=4)
def _load(path: str) -> tuple[SceneRecord, ...]:
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(f"scene database {p} is missing; rebuild with: python -m wana.assets.scenedb")
    return tuple(msgspec.json.decode(p.read_bytes(), type=SceneDB).records)


def get_scene(scene_id: str, path: str | Path | None = None) -> SceneRecord:
    """One record by id. Raises KeyError for an unknown id."""
    for rec in load_scenedb(path):
        if rec.id == scene_id:
            return rec
    raise KeyError(f"no scene {scene_id!r} in the scene database")


def build_scenedb(
    per_room: int = 10, room_types: list[str] | None = None, progress: bool = True, max_tries: int = 20
) -> list[SceneRecord]:
    """Generate and validate ``per_room`` scenes for every room type (seeded, deterministic)."""
    from tqdm import tqdm

    from wana.assets.scene_rules import RULES
    from wana.assets.scenes import generate_scene
    from wana.assets.validate import scene_problems

    rooms = room_types or list(RULES)
    records: list[SceneRecord] = []
    bar = tqdm(total=per_room * len(rooms), disable=not progress, desc="scenes")
    for room in rooms:
        seed = 0
        for k in range(per_room):
            for _ in range(max_tries):
                gen = generate_scene(room, seed)
                seed += 1
                if len(gen.scene.objects) >= 4 and not scene_problems(gen.scene, gen.relations):
                    break
            else:
                raise RuntimeError(f"could not generate a valid {room} scene after {max_tries} seeds")
            records.append(
                SceneRecord(
                    id=f"{room}-{k:03d}",
                    room_type=room,
                    objects=gen.objects,
                    relations=gen.relations,
                    scene=gen.scene,
                    seed=gen.seed,
                )
            )
            bar.update(1)
    bar.close()
    return records


def write_scenedb(records: list[SceneRecord], path: str | Path, command: str) -> Path:
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    db = SceneDB(version=GRAMMAR_VERSION, command=command, records=records)
    tmp = out.with_suffix(".json.tmp")
    tmp.write_bytes(msgspec.json.format(msgspec.json.encode(db), indent=0))
    tmp.replace(out)  # atomic: readers never see a half-written database
    _load.cache_clear()
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m wana.assets.scenedb",
        description="Rebuild the committed scene database from the scene grammar.",
    )
    parser.add_argument("--per-room", type=int, default=10, help="scenes per room type (default 10)")
    parser.add_argument("--out", default=str(SCENEDB_PATH), help="output JSON path")
    parser.add_argument("--rooms", nargs="*", help="only these room types")
    args = parser.parse_args(argv)
    records = build_scenedb(args.per_room, args.rooms)
    cmd = f"python -m wana.assets.scenedb --per-room {args.per_room}"
    path = write_scenedb(records, args.out, cmd)
    n_obj = sum(len(r.scene.objects) for r in records)
    print(f"wrote {len(records)} scenes ({n_obj} objects) to {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
