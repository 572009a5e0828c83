"""The Kubernetes manifests, run as processes: what they start is a working system whose /metrics rise and fall.

Every process is started from its manifest's container (args and env) the way the image's entrypoint
(`wana`) would run it, on loopback: the bus Service (tcp://wana-broker:5555) and the 0.0.0.0 binds
become 127.0.0.1 with free ports, each Secret volume becomes a directory holding exactly the items the
manifest mounts from `wana keys new`, the token Secret becomes a fresh token and the sessions PVC a
temporary directory. Nothing else is added, so a manifest whose command or key mounts are wrong fails here.
"""

from __future__ import annotations

import os
import secrets
import shutil
import socket
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import msgspec
import pytest
import yaml
from prometheus_client.parser import text_string_to_metric_families

from proto.common import Header
from proto.nlp import ParseRequest
from services.orchestrator.registry import SERVICES
from wana.bus.client import Client

pytestmark = [pytest.mark.integration, pytest.mark.slow]

K8S = Path(__file__).resolve().parents[2] / "deploy" / "k8s"
BUS_SERVICE = "tcp://wana-broker:5555"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def workload(name: str) -> dict[str, Any]:
    """The pod spec of the Deployment or StatefulSet called ``name`` in deploy/k8s/."""
    for path in sorted(K8S.glob("*.yaml")):
        for doc in yaml.safe_load_all(path.read_text()):
            if doc and doc["kind"] in ("Deployment", "StatefulSet") and doc["metadata"]["name"] == name:
                return dict(doc["spec"]["template"]["spec"])
    raise KeyError(name)


class Cluster:
    """Processes started from the manifests, with the cluster's names mapped to loopback."""

    def __init__(self, root: Path) -> None:
        self.root = root
        self.keys = root / "keys"
        subprocess.run([sys.executable, "-m", "wana.cli", "keys", "new", str(self.keys)], check=True)
        self.bus = f"tcp://127.0.0.1:{free_port()}"
        self.token = secrets.token_hex(16)
        self.ports: dict[str, int] = {}
        self.procs: list[subprocess.Popen[bytes]] = []

    def _volume(self, name: str, volume: dict[str, Any]) -> str:
        """A directory standing for one pod volume: a Secret's items copied from keys/, or a PVC."""
        where = self.root / "volumes" / name / volume["name"]
        where.mkdir(parents=True, exist_ok=True)
        secret = volume.get("secret")
        if secret is not None:
            assert secret["secretName"] == "wana-bus-keys", secret
            for item in secret["items"]:
                target = where / item["path"]
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(self.keys / item["key"], target)
        else:
            assert "persistentVolumeClaim" in volume, volume
        return str(where)

    def _env_value(self, var: dict[str, Any]) -> str:
        if "value" in var:
            return str(var["value"])
        ref = var["valueFrom"]["secretKeyRef"]
        assert (ref["name"], ref["key"]) == ("wana-gateway-token", "token"), ref
        return self.token

    def start(self, name: str) -> subprocess.Popen[bytes]:
        """Start the (single) container of workload ``name`` as its manifest says."""
        spec = workload(name)
        (container,) = spec["containers"]
        volumes = {v["name"]: self._volume(name, v) for v in spec.get("volumes", [])}
        mounts = {m["mountPath"]: volumes[m["name"]] for m in container.get("volumeMounts", [])}

        def local(text: str) -> str:
            text = text.replace(BUS_SERVICE, self.bus).replace("tcp://0.0.0.0:5555", self.bus)
            for mount_path, directory in mounts.items():
                text = text.replace(mount_path, directory)
            return "127.0.0.1" if text == "0.0.0.0" else text

        args = [local(a) for a in container["args"]]
        for flag in ("--port",):
            if flag in args:  # the container's port, here a free one
                i = args.index(flag) + 1
                self.ports[name] = free_port()
                args[i] = str(self.ports[name])
        env = dict(os.environ)
        env.update({v["name"]: local(self._env_value(v)) for v in container.get("env", [])})
        proc = subprocess.Popen(
            [sys.executable, "-m", "wana.cli", *args],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=open(self.root / f"{name}.log", "wb"),  # noqa: SIM115 - closed with the process
        )
        self.procs.append(proc)
        return proc

    def url(self, name: str, path: str) -> str:
        return f"http://127.0.0.1:{self.ports[name]}{path}"

    def logs(self) -> str:
        return "\n".join(f"--- {p.name}\n{p.read_text()[-3000:]}" for p in sorted(self.root.glob("*.log")))

    def stop(self) -> None:
        for p in self.procs:
            p.terminate()
        for p in self.procs:
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Cluster]:
    c = Cluster(tmp_path_factory.mktemp("cluster"))
    try:
        c.start("wana-broker")
        for service in SERVICES:
            c.start(f"wana-{service}")
        c.start("wana-metrics")
        c.start("wana-gateway")
        yield c
    finally:
        c.stop()


def scrape(url: str) -> dict[tuple[str, tuple[tuple[str, str], ...]], float]:
    """Every sample of a /metrics page: (name, sorted labels) -> value."""
    text = httpx.get(url, timeout=10).text
    return {
        (s.name, tuple(sorted(s.labels.items()))): s.value
        for family in text_string_to_metric_families(text)
        for s in family.samples
    }


def value(samples: dict[Any, float], name: str, **labels: str) -> float:
    return samples.get((name, tuple(sorted(labels.items()))), 0.0)


def wait_for(what: str, check: Callable[[], bool], cluster: Cluster, timeout_s: float = 240) -> None:
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        try:
            if check():
                return
        except httpx.HTTPError:
            pass
        time.sleep(0.25)
    pytest.fail(f"{what} not within {timeout_s} s\n{cluster.logs()}")


def test_the_manifests_start_a_system_whose_gateway_edits_a_document_through_the_workers(cluster):
    metrics = cluster.url("wana-metrics", "/metrics")
    wait_for(
        "every worker registered",
        lambda: all(value(scrape(metrics), "wana_workers", service=s) == 1 for s in SERVICES),
        cluster,
    )
    wait_for(
        "the gateway ready", lambda: httpx.get(cluster.url("wana-gateway", "/healthz")).is_success, cluster
    )
    headers = {"Authorization": f"Bearer {cluster.token}"}
    api = cluster.url("wana-gateway", "/api/documents")
    assert httpx.post(api, json={"text": ""}).status_code == 401  # the token Secret is in force
    created = httpx.post(api, json={"text": "", "doc_id": "deploy"}, headers=headers)
    assert created.status_code == 201, created.text
    before = value(scrape(metrics), "wana_jobs_completed_total", service="nlp")
    text = (
        "A chair is in the office$. A lamp is near the chair$. Eve walks to the chair. Eve sits on the chair."
    )
    edited = httpx.put(f"{api}/deploy/text", json={"text": text}, headers=headers)
    assert edited.status_code == 200, edited.text
    gateway = cluster.url("wana-gateway", "/metrics")
    assert value(scrape(gateway), "wana_gateway_edit_ack_seconds_count") >= 1
    wait_for(
        "the edit's compute",
        lambda: value(scrape(gateway), "wana_gateway_compute_seconds_count") >= 1,
        cluster,
    )
    after = scrape(metrics)
    # the four sentences parse as one ParseBatchRequest (and the document resolves): NLP jobs did run
    assert value(after, "wana_jobs_completed_total", service="nlp") >= before + 1
    assert value(after, "wana_job_latency_seconds_count", service="nlp") >= before + 1
    kinds = [s["kind"] for s in httpx.get(f"{api}/deploy", headers=headers).json()["sentences"]]
    assert kinds == ["scene", "scene", "action", "action"]


def test_the_exported_queue_depth_rises_while_work_is_queued_and_falls_to_zero_after(cluster):
    metrics = cluster.url("wana-metrics", "/metrics")
    wait_for("an nlp worker", lambda: value(scrape(metrics), "wana_workers", service="nlp") == 1, cluster)
    story = " ".join(f"Eve walks to the chair number {i} and sits on it slowly." for i in range(40))
    payloads = [
        msgspec.msgpack.encode(ParseRequest(header=Header(), sentence_id=f"s{i}", text=story))
        for i in range(150)
    ]
    keys = cluster.root / "volumes" / "wana-metrics" / "bus-keys"  # a client's mounted pair
    client = Client(cluster.bus, keys=keys)
    try:
        done_before = value(scrape(metrics), "wana_jobs_completed_total", service="nlp")
        jobs = client.submit_many("nlp", payloads, deadline_s=600)
        depths = []
        for _ in range(20):
            samples = scrape(metrics)
            depths.append(value(samples, "wana_queue_depth", service="nlp"))
            if depths[-1] > 0 and value(samples, "wana_in_flight_jobs", service="nlp") >= 1:
                break
            time.sleep(0.1)
        assert max(depths) > 0, depths
        results = client.wait(jobs, timeout=600)
        assert len(results) == len(jobs)
    finally:
        client.close()
    after = scrape(metrics)
    assert value(after, "wana_queue_depth", service="nlp") == 0
    assert value(after, "wana_in_flight_jobs", service="nlp") == 0
    assert value(after, "wana_jobs_completed_total", service="nlp") >= done_before + len(payloads)
    assert value(after, "wana_broker_up") == 1
