"""``write_outputs``: everything ``wana animate`` writes, from the pipeline's results.

>>> paths = write_outputs("out", scene, motions, commands, sentences, report)
>>> sorted(paths)  # file name -> path
['Eve.bvh', 'animation.mp4', 'report.json', 'scene.glb']
>>> paths.checks["s8"]  # the video's camera checks (in_view, command_visible) by sentence id
[Check(name='in_view', ok=True, ...)]
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import msgspec

from proto.fidelity import Check
from proto.motion_data import Motion
from proto.scene import Scene
from services.render.bvh_export import write_character_bvh
from services.render.camera_checks import staged_checks
from services.render.director import shot_messages
from services.render.gltf_export import write_glb
from services.render.renderer import FrameRenderer, render_mp4
from services.render.report import write_report
from services.render.timeline import as_motion_list, make_captions, place_commands
from services.render.video import FPS


class Outputs(dict[str, Path]):
    """File name -> path of what was written, and the video's camera checks (sentence id -> checks)."""

    def __init__(self) -> None:
        super().__init__()
        self.checks: dict[str, list[Check]] = {}


def write_outputs(
    out_dir: str | Path,
    scene: Scene,
    motions: Iterable[Motion] | Mapping[str, Motion],
    commands: Iterable[Any] | None,
    sentences: Iterable[Any] | None,
    report: Mapping[str, Any] | None,
    *,
    width: int = 640,
    height: int = 480,
    progress: bool = True,
    captions: bool = True,
) -> Outputs:
    """Render and export an animation, and check its camera (services.render.camera_checks).

    Args:
        out_dir: folder to write into (created).
        scene: the composed scene.
        motions: one Motion per character, as a list or a name -> Motion mapping.
        commands: camera/weather commands: ``Command``, ``(sentence_id, Command)`` or ``TimedCommand``.
        sentences: the document's sentences in order (objects with ``id``/``sentence_id`` and ``text``,
            dicts, ``(id, text)`` pairs or strings); used to time commands and for captions.
        report: the pipeline's report (SSG, retrieval choices, costs, diagnostics); a "render"
            section is added.
        width, height: video size in pixels.
        progress: show a tqdm progress bar.
        captions: burn the current sentence into the video.

    Returns:
        File name -> path: "animation.mp4", "scene.glb", "<character>.bvh" for each character,
        "report.json"; its ``checks`` are the in_view and command_visible checks of the video, by
        sentence id, also in the report's render section as "checks".
    """
    from tqdm import tqdm

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    mlist = as_motion_list(motions)
    sentence_list = list(sentences or [])
    timed = place_commands(commands, sentence_list, mlist)
    caps = make_captions(sentence_list, mlist) if captions else []
    paths = Outputs()
    t0 = time.perf_counter()
    with FrameRenderer(scene, mlist, timed, caps, width=width, height=height) as renderer:
        n = renderer.n_frames
        paths.checks = staged_checks(renderer.staging, sentence_list, width=width, height=height)
        with tqdm(total=n + 2 + len(mlist), desc="render", unit="frame", disable=not progress) as bar:
            video = out / "animation.mp4"
            render_mp4(renderer, video, progress=bar.update)  # frame ranges in parallel where cores are free
            paths["animation.mp4"] = video
            render_s = time.perf_counter() - t0
            camera = renderer.staging.camera_track(width, height)
            paths["scene.glb"] = write_glb(out / "scene.glb", scene, mlist, camera=camera)
            bar.update(1)
            for m in mlist:
                p = write_character_bvh(out, m)
                paths[p.name] = p
                bar.update(1)
            render_info = {
                "frames": n,
                "fps": FPS,
                "width": width,
                "height": height,
                "duration_s": n / FPS,
                "render_seconds": round(render_s, 3),
                "commands": [
                    {
                        "frame": c.frame,
                        "kind": c.command.kind,
                        "value": c.command.value,
                        "target": c.command.target,
                    }
                    for c in timed
                ],
                "captions": caps,
                "characters": [
                    {
                        "name": m.character,
                        "look": renderer.rigs[m.character].character.name,
                        "frames": renderer.rigs[m.character].n_frames,
                    }
                    for m in mlist
                ],
                "files": sorted([*paths, "report.json"]),
                "checks": paths.checks,
                "shots": msgspec.to_builtins(shot_messages(renderer.staging.shots)),
            }
            paths["report.json"] = write_report(out / "report.json", report, render_info)
            bar.update(1)
    return paths
