"""``wana assets``: list, show and export catalog objects, database scenes and characters.

wana assets list [categories|scenes|characters|rooms] [--room office]
wana assets show office_chair --attr colour=red --attr style=modern
wana assets show office-003
wana assets export living_room-001 -o out/scene.glb
wana assets export piano -o out/piano.glb --png out/piano.png
wana assets export Eve -o out/eve.glb
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, cast

if TYPE_CHECKING:
    import trimesh


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="wana assets",
        description="Browse and export the asset library: procedural "
        "catalog objects, the scene database and the characters.",
    )
    sub = p.add_subparsers(dest="command", required=True)
    ls = sub.add_parser("list", help="list categories, scenes, characters or room types")
    ls.add_argument(
        "what", nargs="?", default="categories", choices=["categories", "scenes", "characters", "rooms"]
    )
    ls.add_argument("--room", help="only this room type (categories that appear in it, or its scenes)")
    for name, helptext in (
        ("show", "describe an object category, a scene id or a character"),
        ("export", "write an object, scene or character to GLB"),
    ):
        sp = sub.add_parser(name, help=helptext)
        sp.add_argument(
            "name", help="category (e.g. office_chair), scene id (e.g. office-003) or character (Eve)"
        )
        sp.add_argument(
            "--attr",
            action="append",
            default=[],
            metavar="KNOB=VALUE",
            help="object attribute, e.g. colour=red (repeatable)",
        )
        sp.add_argument("--seed", type=int, default=0, help="object variant seed (default 0)")
        if name == "export":
            sp.add_argument("-o", "--output", required=True, help="output .glb path")
            sp.add_argument("--png", help="also write a preview PNG here")
            sp.add_argument("--no-room", action="store_true", help="scenes: leave out floor and walls")
    return p


def _attrs(pairs: list[str]) -> dict[str, str]:
    out = {}
    for pair in pairs:
        if "=" not in pair:
            raise ValueError(f"--attr expects KNOB=VALUE, got {pair!r}")
        k, v = pair.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def _resolve(name: str) -> tuple[str, object]:
    """('object'|'scene'|'character', thing) for a name; raises LookupError with suggestions."""
    from wana.assets import catalog, vocabulary
    from wana.assets.characters import character_names
    from wana.assets.scenedb import load_scenedb

    if name in catalog.categories():
        return "object", name
    chars = {n.lower(): n for n in character_names()}
    if name.lower() in chars:
        return "character", chars[name.lower()]
    try:
        scenes = {r.id: r for r in load_scenedb()}
    except FileNotFoundError:
        scenes = {}
    if name in scenes:
        return "scene", scenes[name]
    cat = vocabulary.lookup(name)
    if cat is not None:
        return "object", cat
    raise LookupError(f"{name!r} is not a category, scene id or character; try `wana assets list`")


def _list(args: argparse.Namespace) -> int:
    from wana.assets import catalog, vocabulary
    from wana.assets.characters import character_names, make_character

    if args.what == "categories":
        cats = vocabulary.categories_in_room(args.room) if args.room else catalog.categories()
        for c in cats:
            info = vocabulary.CATEGORIES[c]
            print(
                f"{c:20s} {catalog.count_variants(c):6d} variants  {info.mount:7s} {', '.join(info.synonyms[:4])}"
            )
        print(f"{len(cats)} categories")
    elif args.what == "rooms":
        for r, syn in vocabulary.ROOM_TYPES.items():
            print(f"{r:14s} {', '.join(syn[:4])}")
    elif args.what == "characters":
        for n in character_names():
            character = make_character(n)
            print(
                f"{n:6s} {character.height:.2f} m  {len(character.vertices)} vertices  "
                f"{len(character.blendshapes)} blendshapes"
            )
    else:
        from wana.assets.scenedb import load_scenedb

        recs = [r for r in load_scenedb() if not args.room or r.room_type == args.room]
        for rec in recs:
            print(
                f"{rec.id:18s} {rec.scene.room.width:.1f}x{rec.scene.room.depth:.1f} m  "
                f"{len(rec.objects):2d} objects  {len(rec.relations):2d} relations"
            )
        print(f"{len(recs)} scenes")
    return 0


def _show(args: argparse.Namespace) -> int:
    kind, thing = _resolve(args.name)
    if kind == "object":
        from wana.assets import catalog, vocabulary

        assert isinstance(thing, str)
        obj = catalog.make_object(thing, _attrs(args.attr), args.seed)
        info = vocabulary.CATEGORIES[thing]
        print(f"category   {thing}  (hypernyms: {' > '.join(vocabulary.hypernyms(thing))})")
        print(f"synonyms   {', '.join(info.synonyms)}")
        print(f"rooms      {', '.join(info.rooms)}   mount: {info.mount}")
        print(f"knobs      {', '.join(info.knobs)}   attributes: {obj.attributes or '{}'}  seed {obj.seed}")
        print(
            f"dims       {obj.dims.round(3).tolist()} m   faces {len(obj.mesh.faces)}   "
            f"collision boxes {len(obj.collision_boxes)}"
        )
        for name, cp in obj.contact_points.items():
            extra = "".join(f", {j} {p.round(3).tolist()}" for j, p in cp.extra.items())
            print(f"contact    {name:10s} {cp.joint} {cp.position.round(3).tolist()}{extra}")
        print(f"stand at   {obj.stand_point.round(3).tolist()}")
        for s in obj.support_surfaces:
            print(
                f"surface    y={s.height:.3f} x/z {s.min_xz.round(3).tolist()} .. {s.max_xz.round(3).tolist()}"
            )
    elif kind == "character":
        from wana.assets.characters import make_character

        assert isinstance(thing, str)
        c = make_character(thing)
        print(
            f"character  {c.name}  height {c.height:.2f} m  vertices {len(c.vertices)}  faces {len(c.faces)}"
        )
        print(f"blendshapes {', '.join(c.blendshapes)}")
    else:
        from wana.assets.scenedb import SceneRecord

        assert isinstance(thing, SceneRecord)
        rec = thing
        r = rec.scene.room
        print(f"scene {rec.id}  room {rec.room_type} {r.width}x{r.depth}x{r.height} m  seed {rec.seed}")
        for o in rec.scene.objects:
            on = f" on {o.support}" if o.support else ""
            print(f"  {o.id:20s} {str(o.attributes or ''):40s} at {list(o.position)} yaw {o.yaw:+.2f}{on}")
        for rel in rec.relations:
            print(f"  {rel.subject} {rel.relation} {rel.object}")
    return 0


def _export(args: argparse.Namespace) -> int:
    from wana.assets import gltf
    from wana.assets.preview import render_mesh

    kind, thing = _resolve(args.name)
    out = Path(args.output)
    mesh: trimesh.Trimesh
    if kind == "object":
        from wana.assets import catalog

        assert isinstance(thing, str)
        obj = catalog.make_object(thing, _attrs(args.attr), args.seed)
        gltf.export_object_glb(obj, out)
        mesh = obj.mesh
    elif kind == "character":
        import trimesh

        from wana.assets.characters import make_character

        assert isinstance(thing, str)
        c = make_character(thing)
        gltf.export_character_glb(c, out)
        mesh = trimesh.Trimesh(c.vertices, c.faces, process=False)
        mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=c.colours[c.faces[:, 0]])
    else:
        from wana.assets.scenedb import SceneRecord

        assert isinstance(thing, SceneRecord)
        gltf.export_scene_glb(thing.scene, out, with_room=not args.no_room)
        # a scene of triangle meshes concatenates to one Trimesh
        mesh = cast("trimesh.Trimesh", gltf.scene_trimesh(thing.scene, with_room=False).to_geometry())
    print(f"wrote {out}")
    if args.png:
        Path(args.png).parent.mkdir(parents=True, exist_ok=True)
        render_mesh(mesh, 512).save(args.png)
        print(f"wrote {args.png}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``wana assets``; returns the exit status."""
    args = _parser().parse_args(argv)
    try:
        return {"list": _list, "show": _show, "export": _export}[args.command](args)
    except (LookupError, ValueError, FileNotFoundError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
