"""A story is staged once: the MP4 and the GLB of one story share the director's plan, and the seat and the
hands' furniture that every candidate camera of a shot asks about are worked out once per skeleton."""

from __future__ import annotations

import numpy as np
import pytest

from proto.common import Header
from proto.render import ExportReply, ExportRequest
from services.render import handlers
from services.render.demo import demo_scene, walk_motion
from services.render.sightlines import Furniture
from services.render.staging import Staging
from services.render.visibility import HANDS, held_under, own_supports, seat_under
from wana.domain.skeleton import JOINT_INDEX


def test_own_supports_equal_the_direct_answers_and_a_new_skeleton_is_never_answered_from_an_old_one() -> None:
    furniture = Furniture.from_boxes([np.array([[[0.0, 0.0, 0.0], [1.0, 0.45, 1.0]]])], ["stool"])
    rng = np.random.default_rng(0)
    frames = np.array([0, 3, 5, 9])
    for _ in range(3):
        joints = rng.uniform(-0.2, 1.2, (10, len(JOINT_INDEX), 3))
        joints[:, JOINT_INDEX["Hips"], 1] = rng.uniform(0.4, 0.6, 10)  # some frames seated on the stool
        pose = joints[frames]
        want = (
            seat_under(pose[:, JOINT_INDEX["Hips"]], furniture),
            held_under(pose[:, [JOINT_INDEX[h] for h in HANDS]], furniture),
        )
        for _ in range(2):  # asked again: the remembered answer, equal
            got = own_supports(joints, frames, furniture)
            assert all(np.array_equal(g, w) for g, w in zip(got, want, strict=True))
    assert (want[0] >= 0).any() or (want[1] >= 0).any()  # the case has something on the stool


@pytest.mark.slow
def test_the_glb_of_a_story_reuses_the_staging_of_its_mp4(monkeypatch: pytest.MonkeyPatch) -> None:
    built: list[int] = []
    build = Staging.build

    def counted(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        built.append(1)
        return build(*args, **kwargs)

    monkeypatch.setattr(Staging, "build", counted)
    monkeypatch.setattr(handlers, "_staged", {"key": None, "staging": None})
    motion = walk_motion("Eve", (-1.0, 1.0), (1.0, 0.0), 20, sentence_id="s1")
    req = ExportRequest(
        header=Header(), format="mp4", scene=demo_scene(), motions=[motion], width=64, height=48
    )
    mp4 = handlers.handle_export(req)
    glb = handlers.handle_export(
        ExportRequest(**{**{f: getattr(req, f) for f in req.__struct_fields__}, "format": "glb"})
    )
    assert isinstance(mp4, ExportReply) and isinstance(glb, ExportReply)
    assert len(built) == 1  # planned once for both files
    assert glb.n_frames == mp4.n_frames and glb.shots == mp4.shots
    moved = walk_motion("Eve", (-1.0, 1.0), (0.5, 0.5), 20, sentence_id="s1")
    handlers.handle_export(ExportRequest(header=Header(), format="glb", scene=demo_scene(), motions=[moved]))
    assert len(built) == 2  # another motion is staged anew
