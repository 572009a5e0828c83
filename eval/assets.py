"""Asset library statistics: categories, variants, scenes, room types, characters, validation failures.

    .venv/bin/python eval/assets.py --json out/eval/assets.json [--quick] [--png out/eval/assets_catalog.png]

Writes exactly the keys of issue 4 to the JSON file; the table also shows how many variants were
built and checked for distinct meshes, how many scenes were validated, and load/build timings.
--quick validates one scene per room type and samples fewer variants (under 30 s).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import numpy as np  # noqa: E402
from tqdm import tqdm  # noqa: E402

SEED = 20240604


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description="Measure the asset library (issue 4) and render a catalog contact sheet."
    )
    parser.add_argument("--json", required=True, help="write the statistics to this JSON file")
    parser.add_argument("--quick", action="store_true", help="subset validation and sampling (under 30 s)")
    parser.add_argument(
        "--png",
        default=str(REPO / "out" / "eval" / "assets_catalog.png"),
        help="contact sheet of every catalog category (PNG)",
    )
    args = parser.parse_args(argv)

    from wana.assets import catalog, vocabulary
    from wana.assets.characters import character_names, make_character
    from wana.assets.preview import contact_sheet
    from wana.assets.scenedb import _load, load_scenedb
    from wana.assets.validate import scene_problems

    cats = catalog.categories()
    t0 = time.perf_counter()
    items = [(c, catalog.make_object(c).mesh) for c in cats]
    build_ms = (time.perf_counter() - t0) / len(cats) * 1000.0

    # Distinctness of enumerated variants on a seeded random sample.
    rng = np.random.default_rng(SEED)
    n_sample = 300 if args.quick else 3000
    pairs = []
    for c in cats:
        space = list(catalog.iter_variants(c))
        pairs.extend((c, space[i]) for i in range(len(space)))
    picks = rng.choice(len(pairs), size=min(n_sample, len(pairs)), replace=False)
    digests = set()
    for i in tqdm(picks, desc="variants", leave=False):
        c, attrs = pairs[i]
        digests.add(catalog.mesh_digest(catalog.make_object(c, dict(attrs))))

    _load.cache_clear()
    t0 = time.perf_counter()
    records = load_scenedb()
    load_s = time.perf_counter() - t0
    to_check = records
    if args.quick:
        seen: dict[str, object] = {}
        for r in records:
            seen.setdefault(r.room_type, r)
        to_check = list(seen.values())
    failures = []
    for rec in tqdm(to_check, desc="validate", leave=False):
        problems = scene_problems(rec.scene, rec.relations)
        if problems:
            failures.append((rec.id, problems[:3]))
    chars = [make_character(n) for n in character_names()]

    stats = {
        "categories": len(cats),
        "variants": catalog.count_variants(),
        "scenes": len(records),
        "room_types": len({r.room_type for r in records}),
        "characters": len(chars),
        "validation_failures": len(failures),
    }
    png = contact_sheet([(c, m) for c, m in items], args.png, cols=15, cell=120)
    rows = [
        ("categories", stats["categories"], f"vocabulary has {len(vocabulary.CATEGORIES)}"),
        ("variants", stats["variants"], f"{len(digests)}/{len(picks)} sampled variants have distinct meshes"),
        ("scenes", stats["scenes"], f"database load {load_s * 1000:.0f} ms"),
        ("room_types", stats["room_types"], ", ".join(sorted({r.room_type for r in records}))[:60] + "..."),
        ("characters", stats["characters"], f"{min(len(c.blendshapes) for c in chars)} blendshapes each"),
        ("validation_failures", stats["validation_failures"], f"{len(to_check)} scenes validated"),
        ("object build", f"{build_ms:.1f} ms", "mean per category, first build (then cached)"),
        ("contact sheet", str(png), ""),
    ]
    print(f"{'metric':22s} {'value':>10s}  note")
    for name, value, note in rows:
        print(f"{name:22s} {value!s:>10s}  {note}")
    for rid, problems in failures:
        print(f"  {rid}: {problems}")
    out = Path(args.json)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(stats, indent=2) + "\n")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
