"""The `wana` command: every sub-command explains itself, bad input gets a clear error."""

import subprocess
import sys

import pytest

from wana.cli import main

SUBCOMMANDS = ["animate", "serve", "parse", "assets", "motion", "broker", "worker"]


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "wana.cli", *args], capture_output=True, text=True, timeout=120
    )


def test_help_lists_every_subcommand():
    out = run("--help")
    assert out.returncode == 0
    for name in SUBCOMMANDS:
        assert name in out.stdout


@pytest.mark.parametrize("name", SUBCOMMANDS)
def test_every_subcommand_has_help(name):
    out = run(name, "--help")
    assert out.returncode == 0, out.stderr
    assert "usage:" in out.stdout.lower()


def test_an_unknown_service_is_refused_with_the_choices(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["worker", "teleport", "--connect", "tcp://127.0.0.1:1"])
    assert exc.value.code == 2
    assert "nlp" in capsys.readouterr().err


def test_animate_names_a_missing_file(tmp_path):
    out = run("animate", str(tmp_path / "nope.txt"), "-o", str(tmp_path / "out"))
    assert out.returncode != 0
    assert "no such file" in out.stderr
