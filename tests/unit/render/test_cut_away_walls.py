"""What hangs on a wall is cut away with its wall: a camera outside the room sees through the wall behind it
(one-sided, culled), and the window on that wall must not stand free in the room in front of the picture."""

from __future__ import annotations

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from services.render.camera import CameraPose
from services.render.renderer import FrameRenderer
from services.render.walls import wall_of, walls_behind

ROOM = Room(room_type="living_room", width=4.0, depth=4.0, height=2.6)
WINDOW = PlacedObject(id="window", category="window", position=(1.97, 0.9, 0.0), yaw=-np.pi / 2)
SOFA = PlacedObject(id="sofa", category="sofa", position=(-1.2, 0.0, 0.0), yaw=np.pi / 2)


def test_a_window_hangs_on_its_nearest_wall_and_a_sofa_on_none():
    assert wall_of(WINDOW, ROOM) == "wall_right"
    assert wall_of(SOFA, ROOM) == ""
    assert walls_behind(np.array([3.5, 1.6, 2.5]), ROOM) == {"wall_right", "wall_front"}
    assert walls_behind(np.array([0.0, 1.6, 0.0]), ROOM) == frozenset()


def test_the_window_on_the_wall_behind_the_camera_is_not_drawn():
    scene = Scene(room=ROOM, objects=[WINDOW, SOFA])
    eye, target = np.array([3.2, 1.5, 0.0]), np.array([-1.0, 0.8, 0.0])  # outside, looking in through it
    pose = CameraPose(eye=eye, target=target, up=np.array([0.0, 1.0, 0.0]), fov_deg=60.0)
    inside = CameraPose(eye=np.array([1.0, 1.5, 0.0]), target=target, up=pose.up, fov_deg=60.0)
    with FrameRenderer(scene, [], [], n_frames=2, width=160, height=120) as r:
        cut = r.render(0, pose)
        near = r.render(1, inside)  # inside the room: the window stays where it hangs (behind the eye)
    empty = Scene(room=ROOM, objects=[SOFA])
    with FrameRenderer(empty, [], [], n_frames=2, width=160, height=120) as r:
        bare = r.render(0, pose)
    assert np.abs(cut.astype(int) - bare.astype(int)).max() <= 2  # as if the window were not there
    assert near.shape == cut.shape
