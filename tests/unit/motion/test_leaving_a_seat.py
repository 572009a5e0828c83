"""Getting up from a seat and walking off: the legs stay out of the seat and the furniture around it."""

from __future__ import annotations

import msgspec
import numpy as np

from proto.scene import PlacedObject, Room, Scene
from services.motion.planning import seat_slots, seat_under
from services.motion.routing import joined_route
from services.motion.synthesis import rise_path
from wana.domain.object_geometry import scene_footprints
from wana.domain.routes import point_rect_distance

ROOM = Room(room_type="music_studio", width=8, depth=8, height=3)


def test_getting_up_beside_a_tucked_in_chair_backs_out_before_stepping_aside():
    """Facing +z (yaw 0): 0.12 m back, 0.46 m to the side. The back part is done before the side part
    starts, so the knees leave the desk's underside before they move along it."""
    rise = np.array([0.46, 0.0, -0.12])
    path = rise_path(rise, 0.0, 61, 2.0)
    assert np.allclose(path[0], 0.0) and np.allclose(path[-1], rise)
    backed = int(np.argmax(path[:, 2] <= rise[2] + 1e-9))  # the first frame fully backed out
    assert path[backed, 0] < 0.01  # not yet aside
    assert np.all(np.diff(path[:, 0]) >= -1e-12) and np.all(np.diff(path[:, 2]) <= 1e-12)


def test_getting_up_onto_the_spot_in_front_is_one_ramp():
    rise = np.array([0.0, 0.0, 0.2])  # forward only
    path = rise_path(rise, 0.0, 61, 2.0)
    assert np.allclose(path[-1], rise) and np.allclose(path[:, 0], 0.0)


def _stool_at_drums() -> tuple[Scene, PlacedObject]:
    """A drum kit and a stool moved to its place to sit (as the orchestrator's seat_at_instruments does)."""
    kit = PlacedObject(id="drum_kit", category="drum_kit", position=(1.0, 0.0, 0.0), yaw=-np.pi / 2)
    place = np.asarray(seat_slots(kit, "seat")[0])
    stool = PlacedObject(id="stool", category="stool", position=(0.0, 0.0, 0.0), yaw=float(kit.yaw) + np.pi)
    own = np.asarray(seat_slots(stool, "seat")[0])
    stool = msgspec.structs.replace(stool, position=(float(place[0] - own[0]), 0.0, float(place[2] - own[2])))
    return Scene(room=ROOM, objects=[kit, stool]), stool


def test_a_character_on_the_stool_at_the_drums_sits_on_the_stool_not_on_the_kits_place():
    """The kit's "sit" point and the stool's are one place; the stool is what the hips are on, and its
    facing (towards the drums) is where getting up goes, not the kit's (away from them, through the stool)."""
    scene, stool = _stool_at_drums()
    slot = np.asarray(seat_slots(stool, "seat")[0])
    under = seat_under(scene, np.array([slot[0], slot[2]]))
    assert under is not None and under[0].id == "stool"


def test_a_route_given_from_elsewhere_is_joined_round_the_seat_from_where_the_walk_starts():
    """The way out was routed from in front of the stool; getting up ended beside it. The walk goes from
    there round the stool to the given route, not back through the stool to its start."""
    stool = PlacedObject(id="stool", category="stool", position=(0.0, 0.0, 0.0), yaw=0.0)
    scene = Scene(room=ROOM, objects=[stool])
    given = np.array([[0.0, -0.35], [0.0, 0.6], [0.0, 2.0], [1.5, 3.0]])  # from behind, over the stool
    start = (0.45, 0.0)  # beside it
    way = joined_route(scene, start, given)
    assert np.allclose(way[0], start) and np.allclose(way[-1], given[-1])
    fp = scene_footprints(scene)
    pts = np.vstack([np.linspace(a, b, 20) for a, b in zip(way[:-1], way[1:], strict=True)])
    assert point_rect_distance(pts, fp).min() > 0.05  # never over the stool
    assert np.array_equal(joined_route(scene, tuple(given[0]), given), given)  # from its own start: as given
