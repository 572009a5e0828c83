"""Objects the actions use that no scene sentence put in the room: added where a person would find them (on
the surface the character was at, else one the sentence names, else the largest table), with an I202, and
then used: picked up, held on through the following sentences, set down where the story says."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from proto.scene import PlacedObject, Room, Scene
from proto.ssg import ActionNode, CharacterNode, ObjectNode, SentenceGraph
from services.orchestrator.backend import InProcessBackend
from services.orchestrator.document import Sentence
from services.orchestrator.session import Orchestrator
from services.orchestrator.stages.props import carried, made_for, prop_needs, provide
from wana.arrays import from_wire
from wana.assets.catalog import world_bounds, world_support_surfaces

ROOM = Room(room_type="office", width=6, depth=6, height=3)
DESK = PlacedObject(id="desk", category="desk", position=(-1.5, 0.0, 1.5), yaw=0.0)
TABLE = PlacedObject(id="table", category="dining_table", position=(1.5, 0.0, -1.0), yaw=0.0)


def _graph(sid: str, name: str, *actions: ActionNode, objects: tuple[ObjectNode, ...] = ()) -> SentenceGraph:
    return SentenceGraph(
        sentence_id=sid, text="", kind="action", characters=[CharacterNode(name=name, actions=list(actions))],
        objects=list(objects),
    )  # fmt: skip


def _sentences(*ids: str) -> list[Sentence]:
    return [Sentence(id=i, start=0, end=1, text="x") for i in ids]


def test_an_object_named_only_in_an_action_goes_on_the_surface_the_character_walked_to():
    graphs = [
        _graph("s1", "John", ActionNode(verb="walk", action="walk", destination="desk")),
        _graph(
            "s2",
            "John",
            ActionNode(verb="read", action="read", target="book"),
            objects=(ObjectNode(id="book", category="book", word="book"),),
        ),  # fmt: skip
    ]
    scene = Scene(room=ROOM, objects=[TABLE, DESK])  # the table has the larger top: the desk must win
    needs = prop_needs(graphs, ["s1", "s2"], scene)
    assert [(n.node.id, n.sentence_id, n.near[:1]) for n in needs] == [("book", "s2", ("desk",))]
    furnished, notes = provide(scene, graphs, _sentences("s1", "s2"))
    book = next(o for o in furnished.objects if o.id == "book")
    assert book.support == "desk"
    (height, corners), *_ = sorted(world_support_surfaces(DESK), key=lambda s: -s[0])
    assert abs(book.position[1] - height) < 1e-3
    lo, hi = world_bounds(book)[:, [0, 2]]
    assert np.all(lo >= corners.min(axis=0) - 1e-6) and np.all(hi <= corners.max(axis=0) + 1e-6)
    assert [(sid, d.code) for sid, d in notes] == [("s2", "I202")] and "desk" in notes[0][1].message


def test_nothing_is_added_for_an_object_the_room_has_or_the_catalog_lacks():
    cup = PlacedObject(id="cup", category="cup", position=(1.5, 0.76, -1.0), support="table")
    graphs = [
        _graph(
            "s1",
            "Sam",
            ActionNode(verb="drink", action="drink", target="cup"),
            ActionNode(verb="walk", action="walk", destination="elevator"),
            objects=(
                ObjectNode(id="cup", category="cup", word="cup"),
                ObjectNode(id="elevator", category="elevator", word="elevator"),
            ),
        )  # fmt: skip
    ]
    assert prop_needs(graphs, ["s1"], Scene(room=ROOM, objects=[TABLE, cup])) == []


def test_a_tool_action_with_no_tool_in_the_room_gets_one_on_the_table():
    graphs = [_graph("s1", "Tom", ActionNode(verb="hammer", action="hammer"))]
    furnished, notes = provide(Scene(room=ROOM, objects=[TABLE]), graphs, _sentences("s1"))
    hammer = [o for o in furnished.objects if o.category == "hammer"]
    assert len(hammer) == 1 and hammer[0].support == "table" and notes[0][1].code == "I202"


def _story(text: str):
    with tempfile.TemporaryDirectory() as tmp:
        orchestrator = Orchestrator(Path(tmp) / "s.db", InProcessBackend(), seed=0)
        try:
            return orchestrator.create(text, doc_id="props").compute()
        finally:
            orchestrator.close()


def test_coffee_named_only_in_an_action_is_a_cup_on_the_table_held_from_the_grasp_to_the_end():
    result = _story(
        "In the kitchen there is a table$.\nSam walks to the table.\nSam drinks coffee.\nSam waves.\n"
    )
    cups = [o for o in result.scene.objects if o.category == "cup"]
    assert len(cups) == 1 and cups[0].support == "table"
    assert any(d.code == "I202" for ds in result.diagnostics.values() for d in ds)
    motion = result.motions["Sam"]
    frames = len(from_wire(motion.root_position))
    held = np.zeros(frames, bool)
    for t in motion.props:
        assert t.object_id == cups[0].id
        held[t.start_frame : t.end_frame] = True
    first = int(np.argmax(held))
    wave = next(s for s in motion.segments if s.action == "wave")
    assert 0 < first and held[first:].all() and wave.end_frame <= frames  # in the hand through the wave


def test_sweeping_a_floor_object_still_gets_a_broom_and_drinking_sees_the_cups():
    rug = PlacedObject(id="rug", category="rug", position=(0.0, 0.0, 0.0), yaw=0.0)
    graphs = [_graph("s1", "Tom", ActionNode(verb="sweep", action="sweep", target="rug"),
                     objects=(ObjectNode(id="rug", category="rug", word="rug"),))]  # fmt: skip
    needs = prop_needs(graphs, ["s1"], Scene(room=ROOM, objects=[TABLE, rug]))
    assert [n.node.category for n in needs] == ["broom"]  # the rug is what is swept, not the tool
    cup = PlacedObject(id="cup", category="cup", position=(1.5, 0.76, -1.0), yaw=0.0, support="table")
    assert [o.id for o in made_for(Scene(room=ROOM, objects=[TABLE, cup, rug]), "drink")] == ["cup"]
    assert made_for(Scene(room=ROOM, objects=[TABLE, cup]), "sit") == []


def test_dishes_washed_at_a_sink_the_parse_dropped_go_in_the_sink_and_the_hands_go_to_its_basin():
    from services.motion.planning import plan_actions

    sink = PlacedObject(id="kitchen_sink", category="kitchen_sink", position=(0.0, 0.0, 2.5), yaw=np.pi)
    scene = Scene(room=ROOM, objects=[TABLE, sink])
    wash = ActionNode(verb="wash", action="wash_dishes", target="plate")  # "at the sink": not in the action
    graphs = [_graph("s1", "Tom", wash, objects=(
        ObjectNode(id="plate", category="plate", word="dishes"),
        ObjectNode(id="kitchen_sink", category="kitchen_sink", word="sink"),
    ))]  # fmt: skip
    furnished, _ = provide(scene, graphs, _sentences("s1"))
    plate = next(o for o in furnished.objects if o.id == "plate")
    assert plate.support == "kitchen_sink"  # not on the table, the room's largest surface
    plan = plan_actions(graphs[0].characters[0], furnished, (0.0, 0.0, 0.0))
    (act,) = [s for s in plan.segments if s.action == "wash_dishes"]
    assert act.target_id == "kitchen_sink" and act.targets  # the basin's own two-hand point


def test_a_microphone_on_its_stand_is_not_added_again_and_the_song_goes_to_it():
    """ "Anna walks to the microphone and sings": the stand microphone is the one sung into (no second one
    with the same id), and the sing names it so the hand goes to its point."""
    from services.orchestrator.stages.props import aimed

    mic = PlacedObject(id="microphone", category="microphone", position=(1.0, 0.0, 1.0), yaw=0.0)
    walk = ActionNode(verb="walk", action="walk", destination="microphone")
    sing = ActionNode(verb="sing", action="sing_with_microphone")
    graphs = [_graph("s1", "Anna", walk, sing)]
    scene = Scene(room=ROOM, objects=[mic, TABLE])
    assert prop_needs(graphs, ["s1"], scene) == []
    characters = {"Anna": (CharacterNode(name="Anna", actions=[walk, sing]), ["s1", "s1"])}
    node, _ = aimed(characters, scene)["Anna"]
    assert node.actions[1].destination == "microphone" and node.actions[0] == walk
    apart = {"Anna": (CharacterNode(name="Anna", actions=[walk, sing]), ["s1", "s2"])}
    assert aimed(apart, scene)["Anna"][0].actions[1].destination == ""  # another sentence: not aimed
    at_table = ActionNode(verb="walk", action="walk", destination="table")
    to_table = {"Anna": (CharacterNode(name="Anna", actions=[at_table, sing]), ["s1", "s1"])}
    assert aimed(to_table, scene)["Anna"][0].actions[1].destination == ""  # a table has no "sing" point


def test_an_added_object_never_takes_an_id_the_room_has():
    from services.orchestrator.stages.props import free_id

    scene = Scene(room=ROOM, objects=[TABLE, msgspec_replace(TABLE, id="table/2")])
    assert free_id(scene, "cup") == "cup" and free_id(scene, "table") == "table/3"


def test_pouring_wine_uses_the_bottle_on_the_table_not_an_added_kettle():
    bottle = PlacedObject(id="bottle", category="bottle", position=(1.5, 0.75, -1.0), support="table")
    assert [o.id for o in made_for(Scene(room=ROOM, objects=[TABLE, bottle]), "pour")] == ["bottle"]
    pour = ActionNode(verb="pour", action="pour", target="glass")
    graphs = [_graph("s1", "John", pour, objects=(ObjectNode(id="glass", category="glass", word="glasses"),))]
    needs = prop_needs(graphs, ["s1"], Scene(room=ROOM, objects=[TABLE, bottle]))
    assert "kettle" not in [n.node.id for n in needs]


def msgspec_replace(obj: PlacedObject, **kw: object) -> PlacedObject:
    import msgspec

    return msgspec.structs.replace(obj, **kw)


def test_a_prop_added_for_an_action_stays_when_a_chair_is_added_too():
    """solo-classroom-10: the chair added for "sits behind her desk" composed the room again and lost the bag
    added for "puts her bag on the teacher's desk" (its I202 said it was there; the check found none)."""
    result = _story(
        "In the classroom there is a teacher's desk$.\nMs Lee enters the classroom.\n"
        "She puts her bag on the teacher's desk.\nMs Lee sits behind her desk.\n"
    )
    codes = {d.code for ds in result.diagnostics.values() for d in ds}
    assert {"I201", "I202"} <= codes  # a chair and the bag added
    bags = [o for o in result.scene.objects if o.category == "handbag"]
    assert len(bags) == 1 and bags[0].support == "teacher_desk"
    assert any(o.category == "chair" for o in result.scene.objects)


def _dining(glasses: int) -> Scene:
    """A dining table with two chairs on each long side facing it and ``glasses`` glasses in its middle."""
    table = PlacedObject(id="dining_table", category="dining_table", position=(0.0, 0.0, 0.0), yaw=0.0)
    (height, _), *_ = world_support_surfaces(table)
    places = [
        ((-0.4, 0.0, -0.75), 0.0),
        ((0.4, 0.0, -0.75), 0.0),
        ((-0.4, 0.0, 0.75), np.pi),
        ((0.4, 0.0, 0.75), np.pi),
    ]
    chairs = [
        PlacedObject(id=f"chair/{i}", category="chair", position=p, yaw=y) for i, (p, y) in enumerate(places)
    ]
    cups = [
        PlacedObject(
            id=f"glass/{i}", category="glass", position=(0.25 * i, height, 0.0), support="dining_table"
        )
        for i in range(glasses)
    ]
    return Scene(
        room=Room(room_type="dining_room", width=6, depth=6, height=3), objects=[table, *chairs, *cups]
    )


def _they(sid: str, names: tuple[str, ...], action: ActionNode) -> SentenceGraph:
    people = [CharacterNode(name=n, actions=[action]) for n in names]
    return SentenceGraph(sentence_id=sid, text="", kind="action", characters=people)


def test_several_drinkers_and_one_glass_get_a_glass_each_in_front_of_a_place_at_the_table():
    """group-dining_room-04: "They drink." with Eve, John and Nora at the table and one glass on it."""
    names = ("Eve", "John", "Nora")
    graphs = [
        _they("s1", names, ActionNode(verb="sit", action="sit", target="dining_table")),
        _they("s2", names, ActionNode(verb="drink", action="drink")),
    ]
    scene = _dining(1)
    furnished, notes = provide(scene, graphs, _sentences("s1", "s2"))
    added = furnished.objects[len(scene.objects) :]
    # the room's kind, one for each beyond the first, and one more: the first stands in the middle, out of
    # reach of every place, so three places get one
    assert [o.category for o in added] == ["glass", "glass", "glass"]
    assert len({o.id for o in furnished.objects}) == len(furnished.objects)
    assert all(o.support == "dining_table" for o in added)
    seats = [np.array([-0.4, -0.75]), np.array([0.4, -0.75]), np.array([-0.4, 0.75]), np.array([0.4, 0.75])]
    nearest = [
        min(range(4), key=lambda i: np.hypot(o.position[0] - seats[i][0], o.position[2] - seats[i][1]))
        for o in added
    ]
    assert len(set(nearest)) == 3  # three different places
    for o, i in zip(added, nearest, strict=True):
        assert (
            np.hypot(o.position[0] - seats[i][0], o.position[2] - seats[i][1]) < 0.6
        )  # in reach of the seat
    messages = [d.message for sid, d in notes if sid == "s2" and d.code == "I202"]
    assert len(messages) == 3 and "for John" in messages[0] and "for Nora" in messages[1]
    assert all("3 characters drink and the room has 1 glass" in m for m in messages[:2])
    assert "a place there has no glass in reach" in messages[2]


def test_drinkers_at_a_table_with_a_glass_each_in_its_middle_get_one_at_their_places():
    """group-dining_room-04: three glasses for three drinkers, but in the middle of the table, 1.1 m from
    Nora's chair (a seated drinker reaches 0.9 m): she drank with an empty hand. Each place a drinker may
    sit at gets one in reach until three places have one."""
    names = ("Eve", "John", "Nora")
    graphs = [
        _they("s1", names, ActionNode(verb="sit", action="sit", target="dining_table")),
        _they("s2", names, ActionNode(verb="drink", action="drink")),
    ]
    scene = _dining(3)
    furnished, _ = provide(scene, graphs, _sentences("s1", "s2"))
    added = furnished.objects[len(scene.objects) :]
    assert [o.category for o in added] == ["glass"] * 3
    seats = [np.array([x, z]) for x in (-0.4, 0.4) for z in (-0.75, 0.75)]
    reached = {
        i
        for o in added
        for i, s in enumerate(seats)
        if np.hypot(o.position[0] - s[0], o.position[2] - s[1]) < 0.6
    }
    assert len(reached) == 3


def test_drinkers_with_a_glass_each_or_one_drinker_get_nothing_more():
    names = ("Eve", "John", "Nora")
    drink = ActionNode(verb="drink", action="drink")
    full = _dining(3)
    assert provide(full, [_they("s1", names, drink)], _sentences("s1")) == (full, [])
    one = _dining(1)
    assert provide(one, [_they("s1", ("Eve",), drink)], _sentences("s1")) == (one, [])


def test_a_bag_added_for_a_put_is_in_the_hand_from_the_start_and_put_on_the_desk_the_sentence_names():
    desk = PlacedObject(id="teacher_desk", category="teacher_desk", position=(0.0, 0.0, 1.5), yaw=np.pi)
    scene = Scene(room=Room(room_type="classroom", width=7, depth=7, height=3), objects=[desk])
    bag = ObjectNode(id="handbag", category="handbag", word="bag")
    put = ActionNode(verb="put", action="put_down", target="handbag")
    graphs = [
        _graph("s1", "Ms Lee", ActionNode(verb="enter", action="walk")),
        _graph(
            "s2",
            "Ms Lee",
            put,
            objects=(bag, ObjectNode(id="teacher_desk", category="teacher_desk", word="desk")),
        ),
    ]
    furnished, _ = provide(scene, graphs, _sentences("s1", "s2"))
    (added,) = [o for o in furnished.objects if o.category == "handbag"]
    assert added.support == "teacher_desk"
    characters = {
        "Ms Lee": (
            CharacterNode(name="Ms Lee", actions=[graphs[0].characters[0].actions[0], put]),
            ["s1", "s2"],
        )
    }
    aimed_at, holding = carried(characters, furnished, {added.id})
    assert holding == {"Ms Lee": added.id}
    assert aimed_at["Ms Lee"][0].actions[1].destination == "teacher_desk"  # the parse dropped "on the desk"
    assert carried(characters, furnished, set()) == (characters, {})  # a bag the room had: picked up there
    read = ActionNode(verb="read", action="read", target="handbag")  # first used otherwise: not brought
    first_read = {"Ms Lee": (CharacterNode(name="Ms Lee", actions=[read, put]), ["s1", "s2"])}
    assert carried(first_read, furnished, {added.id})[1] == {}


def test_ms_lee_comes_in_with_her_bag_and_puts_it_from_her_hand_on_the_desk():
    """solo-classroom-10: the bag added on the desk was "put" there from an empty hand (0.05 m off it)."""
    result = _story(
        "In the classroom there is a teacher's desk$.\nMs Lee enters the classroom.\n"
        "She puts her bag on the teacher's desk.\nMs Lee waves.\n"
    )
    (bag,) = [o for o in result.scene.objects if o.category == "handbag"]
    notes = [d.message for ds in result.diagnostics.values() for d in ds if d.code == "I202"]
    assert (
        "Ms Lee brings the handbag: in the hand from Ms Lee's first frame, then put on the teacher desk"
        in notes
    )
    motion = result.motions["Ms Lee"]
    tracks = sorted((t for t in motion.props if t.object_id == bag.id), key=lambda t: t.start_frame)
    assert tracks and tracks[0].start_frame == 0  # in her hand from her first frame
    put = next(s for s in motion.segments if s.action == "put_down")
    held_until = max(t.end_frame for t in tracks if t.start_frame < put.end_frame)
    assert held_until >= put.end_frame - 1  # carried up to the release
    last = from_wire(tracks[-1].position)[-1]
    (height, corners), *_ = sorted(world_support_surfaces(bag_desk(result.scene)), key=lambda s: -s[0])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    assert lo[0] - 0.05 <= last[0] <= hi[0] + 0.05 and lo[1] - 0.05 <= last[2] <= hi[1] + 0.05  # on the desk


def bag_desk(scene: Scene) -> PlacedObject:
    return next(o for o in scene.objects if o.id == "teacher_desk")


def test_a_photo_of_a_sculpture_in_a_room_with_no_table_is_taken_with_a_camera_brought_along():
    """solo-gallery-12: the sculpture is what the photo is of, never in the hand; nothing can hold the camera
    the action needs, so Nora brings it (in the hand from her first frame)."""
    sculpture = PlacedObject(id="sculpture", category="sculpture", position=(0.0, 0.0, 1.0), yaw=0.0)
    photo = ActionNode(verb="take", action="take_photo", target="sculpture")
    graphs = [_graph("s1", "Nora", photo, objects=(ObjectNode(id="sculpture", category="sculpture",
                                                                word="sculpture"),))]  # fmt: skip
    scene = Scene(room=ROOM, objects=[sculpture])
    needs = prop_needs(graphs, ["s1"], scene)
    assert [(n.node.category, n.holder) for n in needs] == [("camera", "Nora")]
    furnished, notes = provide(scene, graphs, _sentences("s1"))
    (camera,) = [o for o in furnished.objects if o.category == "camera"]
    assert camera.support == "" and "with Nora" in notes[0][1].message
    characters = {"Nora": (CharacterNode(name="Nora", actions=[photo]), ["s1"])}
    _, holding = carried(characters, furnished, {camera.id})
    assert holding == {"Nora": camera.id}


def test_pouring_into_a_glass_the_room_lacks_adds_the_glass_and_something_to_pour_with():
    pour = ActionNode(verb="pour", action="pour", target="glass", destination="glass")
    graphs = [_graph("s1", "Anna", pour, objects=(ObjectNode(id="glass", category="glass", word="glass"),))]
    needs = prop_needs(graphs, ["s1"], Scene(room=ROOM, objects=[TABLE]))
    assert [n.node.category for n in needs] == ["glass", "kettle"]


def test_his_own_phone_is_in_his_hand_from_the_start_a_phone_on_the_table_is_not():
    call = ActionNode(verb="call", action="call_with_phone", target="phone")
    graphs = [_graph("s1", "Tom", call, objects=(ObjectNode(id="phone", category="phone", word="phone"),))]
    furnished, _ = provide(Scene(room=ROOM, objects=[TABLE]), graphs, _sentences("s1"))
    (phone,) = [o for o in furnished.objects if o.category == "phone"]
    assert phone.support == "table"
    characters = {"Tom": (CharacterNode(name="Tom", actions=[call]), ["s1"])}
    _, own = carried(characters, furnished, {phone.id}, {"s1": "He calls someone on his phone."})
    _, theirs = carried(characters, furnished, {phone.id}, {"s1": "He calls someone on the phone."})
    assert own == {"Tom": phone.id} and theirs == {}


def test_onions_chopped_on_the_cutting_board_lie_on_the_board():
    board = PlacedObject(id="cutting_board", category="cutting_board", position=(1.5, 0.75, -1.0),
                         yaw=0.0, support="table")  # fmt: skip
    chop = ActionNode(verb="chop", action="chop", target="vegetable")
    graphs = [_graph("s1", "Nora", chop, objects=(
        ObjectNode(id="vegetable", category="vegetable", word="onions"),
        ObjectNode(id="cutting_board", category="cutting_board", word="cutting board"),
    ))]  # fmt: skip
    furnished, notes = provide(Scene(room=ROOM, objects=[TABLE, board]), graphs, _sentences("s1"))
    (onions,) = [o for o in furnished.objects if o.category == "vegetable"]
    assert onions.support == "cutting_board" and notes[0][1].code == "I202"


def test_vegetables_chopped_on_the_board_at_the_counter_lie_on_the_board_not_the_counter():
    counter = PlacedObject(
        id="kitchen_counter", category="kitchen_counter", position=(1.0, 0.0, -2.0), yaw=0.0
    )
    (height, _), *_ = world_support_surfaces(counter)
    board = PlacedObject(id="cutting_board", category="cutting_board", position=(1.0, height, -2.0),
                         yaw=0.0, support="kitchen_counter")  # fmt: skip
    chop = ActionNode(verb="chop", action="chop", target="vegetable")
    graphs = [_graph("s1", "Anna", chop, objects=(
        ObjectNode(id="kitchen_counter", category="kitchen_counter", word="counter"),
        ObjectNode(id="vegetable", category="vegetable", word="vegetables"),
        ObjectNode(id="cutting_board", category="cutting_board", word="cutting board"),
    ))]  # fmt: skip
    furnished, _ = provide(Scene(room=ROOM, objects=[counter, board]), graphs, _sentences("s1"))
    (veg,) = [o for o in furnished.objects if o.category == "vegetable"]
    assert veg.support == "cutting_board"


def test_what_a_tool_works_on_is_never_brought_in_the_hand():
    """solo-workshop-19: "saws the plank" in a room where nothing holds a plank: the saw is the held thing,
    the plank is not carried from the first frame (it took the hand the saw needed)."""
    saw = PlacedObject(id="saw", category="saw", position=(1.5, 0.76, -1.0), support="table")
    cut = ActionNode(verb="saw", action="saw", target="wood_plank")
    plank = ObjectNode(id="wood_plank", category="wood_plank", word="plank")
    graphs = [_graph("s1", "Mr Garcia", cut, objects=(plank,))]
    needs = prop_needs(graphs, ["s1"], Scene(room=ROOM, objects=[TABLE, saw]))
    assert [(n.node.id, n.holder) for n in needs] == [("wood_plank", "")]
    _, holding = carried(
        {"Mr Garcia": (CharacterNode(name="Mr Garcia", actions=[cut]), ["s1"])},
        Scene(room=ROOM, objects=[TABLE, saw, PlacedObject(id="wood_plank", category="wood_plank")]),
        {"wood_plank"},
        {"s1": "He saws his plank."},
    )
    assert holding == {}  # his own plank is still what the saw works on, not what the hand holds
