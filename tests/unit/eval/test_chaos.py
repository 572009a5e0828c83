"""eval/chaos.py --quick: across network namespaces, under delay, loss, kills and a partition, no acknowledged
edit is lost and no reply is duplicated (needs root and ip netns; skips with the reason elsewhere)."""

from __future__ import annotations

import asyncio
import importlib.util
import json
import random
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SCRIPT = REPO / "eval" / "chaos.py"


def _chaos():
    spec = importlib.util.spec_from_file_location("wana_eval_chaos", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def test_the_proxy_delays_in_order_and_a_partition_holds_every_byte_until_it_heals():
    chaos = _chaos()

    async def run() -> tuple[list[bytes], float, float]:
        async def echo(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
            while data := await reader.read(65536):
                writer.write(data)
                await writer.drain()
            writer.close()

        server = await asyncio.start_server(echo, "127.0.0.1", 0)
        port = server.sockets[0].getsockname()[1]
        proxy = chaos.Proxy(("127.0.0.1", 0), ("127.0.0.1", port), random.Random(1))
        await proxy.start()
        reader, writer = await asyncio.open_connection("127.0.0.1", proxy._server.sockets[0].getsockname()[1])
        got: list[bytes] = []
        started = asyncio.get_running_loop().time()
        for i in range(20):
            writer.write(b"%03d" % i)
            await writer.drain()
        while sum(len(g) for g in got) < 60:
            got.append(await asyncio.wait_for(reader.read(65536), 5))
        round_trip = asyncio.get_running_loop().time() - started
        healing = asyncio.create_task(proxy.partition(0.5))
        await asyncio.sleep(0.05)
        writer.write(b"held")
        await writer.drain()
        held_from = asyncio.get_running_loop().time()
        after = await asyncio.wait_for(reader.read(65536), 5)
        waited = asyncio.get_running_loop().time() - held_from
        await healing
        got.append(after)
        writer.close()
        await proxy.close()
        server.close()
        return got, round_trip, waited

    got, round_trip, waited = asyncio.run(run())
    assert b"".join(got) == b"".join(b"%03d" % i for i in range(20)) + b"held"
    assert round_trip >= 2 * (chaos.DELAY_S - chaos.JITTER_S)  # both directions are delayed
    assert waited >= 0.4  # nothing crossed the partition


@pytest.mark.slow
def test_the_quick_chaos_run_loses_no_acknowledged_edit_and_duplicates_no_reply(tmp_path):
    why = _chaos().unavailable_reason()
    if why:
        pytest.skip(f"eval/chaos.py {why}")
    out = tmp_path / "chaos.json"
    done = subprocess.run(
        [sys.executable, str(SCRIPT), "--quick", "--json", str(out)],
        capture_output=True,
        text=True,
        timeout=900,
        cwd=REPO,
    )
    assert out.is_file(), done.stderr[-4000:]
    result = json.loads(out.read_text())
    assert set(result) == {
        "edits_acked",
        "edits_lost",
        "replies_duplicated",
        "jobs_failed_clearly",
        "recovery_s_p95",
        "broker_rss_mb_max",
    }
    assert result["edits_acked"] >= 200, result
    assert result["edits_lost"] == 0, done.stderr[-4000:]
    assert result["replies_duplicated"] == 0, done.stderr[-4000:]
    assert done.returncode == 0, done.stderr[-4000:]
