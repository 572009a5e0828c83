"""MP4 export jobs: progress is the frames the render service rendered of the total, and cancel stops it.

Real gateway, real render service (in process). The job's video has every frame of the animation, the
same frames the one-call MP4 export gives (within the encoder's noise); a cancelled job stops between
chunks, with frames left unrendered, and has no file.
"""

from __future__ import annotations

import io
import time
from typing import Any

import httpx
import numpy as np
import pytest

from services.gateway import videojobs
from services.gateway.server import GatewayThread
from services.gateway.settings import Settings

pytestmark = [pytest.mark.integration, pytest.mark.slow]

STORY = "In the kitchen there is a table$. Ann walks to the table. Ann waves. Ann walks to the door."
SIZE = {"width": 96, "height": 64}


@pytest.fixture(scope="module")
def gw(tmp_path_factory: pytest.TempPathFactory) -> Any:
    pytest.importorskip("services.render.handlers", reason="needs the render service")
    db = tmp_path_factory.mktemp("videojobs") / "sessions.sqlite"
    with GatewayThread(Settings(db=db, backend="inprocess")) as g:
        yield g


def _frames(video: bytes) -> list[np.ndarray]:
    import av

    with av.open(io.BytesIO(video), mode="r") as container:
        return [f.to_ndarray(format="rgb24") for f in container.decode(video=0)]


def test_a_job_reports_frames_rendered_of_the_total_and_its_file_is_the_whole_video(gw: Any) -> None:
    with httpx.Client(base_url=gw.base_url, timeout=600) as http:
        doc = http.post("/api/documents", json={"text": STORY}).json()["doc_id"]
        job = http.post(f"/api/documents/{doc}/export/mp4/jobs", params=SIZE)
        assert job.status_code == 202, job.text
        jid = job.json()["job_id"]
        seen: list[tuple[int, int]] = []
        deadline = time.monotonic() + 600
        while True:
            s = http.get(f"/api/documents/{doc}/export/mp4/jobs/{jid}").json()
            seen.append((s["done"], s["total"]))
            if s["state"] != "running" or time.monotonic() > deadline:
                break
            time.sleep(0.05)
        assert s["state"] == "done", s
        total = s["total"]
        assert total > 2 * videojobs.CHUNK_FRAMES, "the story is long enough for several chunks"
        assert s["done"] == total and s["percent"] == 100.0
        partial = sorted({d for d, t in seen if t == total and 0 < d < total})
        assert partial, f"no progress between 0 and {total} frames was seen: {seen[:5]}...{seen[-5:]}"
        video = http.get(f"/api/documents/{doc}/export/mp4/jobs/{jid}/file")
        assert video.status_code == 200 and video.headers["content-type"] == "video/mp4"
        one_call = http.get(f"/api/documents/{doc}/export/mp4", params=SIZE)
        assert one_call.status_code == 200
    got, want = _frames(video.content), _frames(one_call.content)
    assert len(got) == len(want) == total

    def diff(a: int, b: int) -> float:
        return float(np.abs(got[a].astype(int) - want[b].astype(int)).mean())

    # each frame is the one-call video's frame of the same index (the chunks are encoded apart: noise)
    for k in (3, total // 3, total // 2, total - 4):
        here = diff(k, k)
        assert here < 4.0, (k, here)
        assert here <= min(diff(k, k + d) for d in (-3, -2, 2, 3)) + 0.5, k


def test_a_cancelled_job_stops_rendering_and_has_no_file(gw: Any) -> None:
    with httpx.Client(base_url=gw.base_url, timeout=600) as http:
        doc = http.post("/api/documents", json={"text": STORY + " Ann sits down."}).json()["doc_id"]
        jid = http.post(f"/api/documents/{doc}/export/mp4/jobs", params=SIZE).json()["job_id"]
        url = f"/api/documents/{doc}/export/mp4/jobs/{jid}"
        deadline = time.monotonic() + 600
        while http.get(url).json()["done"] == 0 and time.monotonic() < deadline:
            time.sleep(0.02)
        assert http.delete(url).status_code == 200
        while (s := http.get(url).json())["state"] == "running" and time.monotonic() < deadline:
            time.sleep(0.05)
        assert s["state"] == "cancelled", s
        assert 0 < s["done"] < s["total"], s
        time.sleep(0.5)
        assert http.get(url).json()["done"] == s["done"], "rendering went on after the cancel"
        assert http.get(f"{url}/file").status_code == 409
        assert http.get(f"/api/documents/{doc}/export/mp4/jobs/nope").status_code == 404
