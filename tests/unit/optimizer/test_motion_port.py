"""The optimiser's motion re-synthesis is handed over by the composition root, never imported."""

from __future__ import annotations

import subprocess
import sys

import pytest

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode
from services.optimizer import motion_port
from services.optimizer.resynthesis import motion_service_fn
from wana.arrays import from_wire
from wana.compose import compose
from wana.domain.units import FPS

SCENE = Scene(
    room=Room(room_type="office", width=5.0, depth=5.0, height=3.0),
    objects=[PlacedObject(id="chair", category="chair", position=(1.0, 0.0, 1.0))],
)
EVE = CharacterNode(name="Eve", actions=[ActionNode(verb="walk", action="walk", destination="chair")])


def test_without_a_composition_root_the_optimiser_says_who_must_wire_it(monkeypatch):
    monkeypatch.setattr(motion_port, "_installed", None)
    with pytest.raises(motion_port.MotionSynthesisMissing, match="wana worker optimizer"):
        motion_service_fn(EVE, (0.0, 0.0, 0.0))


def test_an_injected_synthesis_is_what_the_optimiser_runs():
    calls = []
    real = motion_port.installed()

    def recording(character, scene, start, route_fn):
        calls.append((character.name, start))
        return real.character_motion(character, scene, start, route_fn)

    fake = motion_port.MotionSynthesis(character_motion=recording, seated_action=real.seated_action)
    motion = motion_service_fn(EVE, (0.5, 0.5, 0.0), synthesis=fake)(SCENE)
    assert calls == [("Eve", (0.5, 0.5, 0.0))]
    assert motion.character == "Eve" and motion.fps == FPS
    root = from_wire(motion.root_position)
    assert root.shape[0] > 1  # a real walk towards the chair


def test_compose_wires_the_motion_services_planning_and_synthesis():
    compose()
    motion = motion_service_fn(EVE, (0.5, 0.5, 0.0))(SCENE)
    assert any(s.action == "walk" for s in motion.segments)


def test_the_optimizer_package_loads_no_motion_module():
    code = (
        "import sys, services.optimizer.handlers, services.optimizer.verify;"
        "print(sorted(m for m in sys.modules if m.startswith('services.') "
        "and not m.startswith('services.optimizer')))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
