"""Objects the story's actions use that the scene sentences never put in the room, added before motion.

"John reads a newspaper", "Sam drinks coffee" (a cup: the catalog's synonyms), "Leo plays the guitar" in a room
whose scene sentences never named them; "Tom hammers" with no hammer anywhere. Each such object is placed
where a person would find it: a small object on the surface the character was last at ("walks to the desk
and answers the phone": on the desk), else on a surface the same sentence names ("takes a book from the
bookshelf"), else on the room's largest table; a floor object (a guitar, a dumbbell) on the floor beside
that place. The placement is direct, on the composed room (nothing else moves), and the sentence gets an
I202 diagnostic saying what was added and where. Where nothing can hold it, the room is left as it is and the
action's own check says so (the object is missing; nothing passes silently).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import ModuleType

import msgspec
import numpy as np

from proto.common import Span
from proto.scene import PlacedObject, Scene
from proto.ssg import ActionNode, CharacterNode, Diagnostic, ObjectNode, SentenceGraph
from services.orchestrator.document import Sentence
from wana.domain.actions import get_clip, names_object
from wana.domain.object_geometry import find_object

# The object an action uses when the sentence names none ("Tom hammers", "She drinks"): catalog categories.
DEFAULT_PROP = {
    "drink": "cup",
    "call_with_phone": "phone",
    "pick_up_phone_answer": "phone",
    "text_on_phone": "phone",
    "hammer": "hammer",
    "saw": "saw",
    "screw": "screwdriver",
    "drill": "drill",
    "read": "book",
    "read_newspaper": "book",
    "sing_with_microphone": "microphone",
    "listen_with_headphones": "headphones",
    "play_guitar": "guitar",
    "play_violin": "violin",
    "play_flute": "flute",
    "eat_snack": "plate",
    "lift_weights": "dumbbell",
    "take_photo": "camera",
    "sweep": "broom",
    "pour": "kettle",
    "use_tablet": "tablet",
}
HELD_KINDS = ("handheld", "tool")  # interactions whose object is held in the hand
TABLE_HEIGHT = (0.35, 1.25)  # metres: surfaces a standing or seated person puts things on
GAP = 0.03  # metres between an added object and what already stands there
EDGE = 0.06  # metres an added object keeps from its surface's edge
FLOOR_RING = (0.35, 0.6, 0.9)  # metres beside the anchor's footprint where a floor object may stand
POURED_FROM = ("bottle",)  # drinkware one pours from, not one's own glass
SEAT_REACH = 0.6  # metres from a table top's edge to a seat's sitting point: a seat at that table
PLACE_REACH = 0.6  # metres from a sitting point to a cup that is that place's own (the planner reaches 0.9)


@dataclass(frozen=True)
class Need:
    """One object to add: its node, the sentence that first uses it, and where the character was then."""

    node: ObjectNode
    sentence_id: str
    near: tuple[str, ...]  # object ids to put it on / beside, best first
    action: str = ""  # the action that works on it there ("wash_dishes": the dishes go where one washes)
    why: str = ""  # what the diagnostic says it is for, when not "the story uses the <word>"
    owner: str = ""  # the character it is added for, when one of several ("They drink": one glass each)
    holder: str = ""  # the character whose held action needs it ("takes a photo": the camera in Nora's hand)


def _catalog() -> ModuleType:
    """The asset catalog, imported on first use (the orchestrator runs without it in some tests)."""
    from wana.assets import catalog

    return catalog


def _known(category: str) -> bool:
    try:
        return category in set(_catalog().categories())
    except Exception:  # noqa: BLE001 - no catalog: nothing can be added
        return False


def _mount(category: str) -> str:
    from wana.assets import vocabulary

    info = vocabulary.CATEGORIES.get(category)
    return info.mount if info is not None else "floor"


def clip_kind(action: ActionNode) -> str:
    try:
        clip = get_clip(action.action) if action.action else None
    except KeyError:
        return ""
    return clip.interaction.object if clip is not None and clip.interaction is not None else ""


def _usable(scene: Scene, action: str) -> list[PlacedObject]:
    """The small objects of the room the action can use: a "pick_up" point and the action's own point (or
    the action's name names them: a phone for "text_on_phone")."""
    keys = {action, action.split("_")[0]}
    out = []
    for o in scene.objects:
        try:
            points = set(_catalog().asset_for(o).contact_points)
        except Exception:  # noqa: BLE001 - unknown category
            continue
        if "pick_up" in points and (keys & points or names_object(action, o.category)):
            out.append(o)
    return out


def holdable(placed: PlacedObject) -> bool:
    """Whether an object can be taken in the hand at all (a "pick_up" point; a sculpture has none)."""
    try:
        return "pick_up" in _catalog().asset_for(placed).contact_points
    except Exception:  # noqa: BLE001 - unknown category
        return False


def _made_for(scene: Scene, action: str) -> bool:
    """Whether the room already has a small object the action can use."""
    return bool(_usable(scene, action))


def made_for(scene: Scene, action: str) -> list[PlacedObject]:
    """The small objects of the room a held action can use when its sentence names none ("drinks water":
    the cups; "calls someone": the phones): a "pick_up" point and the action's own point."""
    try:
        clip = get_clip(action) if action else None
    except KeyError:
        return []
    if clip is None or clip.interaction is None or clip.interaction.object not in HELD_KINDS:
        return []
    return _usable(scene, action)


def worked_at(action: ActionNode, scene: Scene) -> list[PlacedObject]:
    """The small objects of the room an action at a surface that names nothing can be done at ("Lucy eats"
    at the table: the plates and bowls, their "eat" point); none for any other action."""
    named = action.target or action.instrument or action.destination
    return [] if named or clip_kind(action) != "surface" else _usable(scene, action.action)


def prop_needs(graphs: Sequence[SentenceGraph], sentence_ids: Sequence[str], scene: Scene) -> list[Need]:
    """The objects action sentences use that the room lacks, in story order (one per id)."""
    out: list[Need] = []
    wanted: set[str] = set()
    last_at: dict[str, list[str]] = {}  # character -> object ids it went to or used, latest last

    def present(ref: str) -> bool:
        return find_object(scene, ref) is not None or ref in wanted

    def fits(ref: str, action: str, kind: str) -> bool:
        """Whether a named object is the one the action uses ("with the hammer"), not what it works on
        ("sweeps the floor", "hammers a nail": the broom, the hammer are still needed) nor what it is aimed
        at ("takes a photo of the sculpture": a camera is still needed, the sculpture is never in the hand)."""
        placed = find_object(scene, ref)
        if placed is None:
            return True  # to be added from the sentence's own object
        return placed in made_for(scene, action) or (kind != "tool" and holdable(placed))

    for g, sid in zip(graphs, sentence_ids, strict=True):
        if g.kind != "action":
            continue
        named = {o.id: o for o in g.objects}
        for c in g.characters:
            for a in c.actions:
                refs = [r for r in (a.target, a.instrument, a.destination) if r]
                here = [r for r in refs if find_object(scene, r) is not None]
                # what else the sentence names in the room comes next ("washes the dishes at the sink":
                # the parse keeps the dishes only; they go in the sink, not on the table last sat at)
                here += _nearest_first(scene, [o.id for o in g.objects if o.id not in refs])
                for ref in refs:
                    node = named.get(ref)
                    if node is None or present(ref) or present(node.category) or not _known(node.category):
                        continue
                    near = (*here, *reversed(last_at.get(c.name, [])))
                    # no holder: a named thing ("drinks from the cup") the room cannot hold stays missing, and
                    # its check says so; only an instrument the sentence leaves unsaid comes with the character
                    out.append(Need(node, sid, tuple(dict.fromkeys(near)), a.action))
                    wanted |= {node.id, node.category}
                kind = clip_kind(a)
                default = DEFAULT_PROP.get(a.action, "")
                if (
                    kind in HELD_KINDS
                    and default
                    and _known(default)
                    # what it is poured into is not what one pours with ("pours water into a glass")
                    and not any(present(r) and fits(r, a.action, kind) for r in refs if r != a.destination)
                    and default not in wanted
                    and not _made_for(scene, a.action)
                    and find_object(scene, default) is None  # one there that stays put: the hand goes to it
                ):
                    node = ObjectNode(id=default, category=default, word=default.replace("_", " "))
                    near = (*here, *reversed(last_at.get(c.name, [])))
                    out.append(Need(node, sid, tuple(dict.fromkeys(near)), holder=c.name))
                    wanted |= {default}
                last_at.setdefault(c.name, []).extend(here)
        out.extend(_one_each(g, sid, scene, out, last_at))
    return out


def _nearest_first(scene: Scene, refs: list[str]) -> list[str]:
    """The refs found in the room, one resting on another of them first ("walks to the counter and chops
    vegetables on the cutting board": the vegetables go on the board, not beside it on the counter)."""
    found = [(r, o) for r in refs if (o := find_object(scene, r)) is not None]
    ids = {o.id for _, o in found}
    return [r for r, o in sorted(found, key=lambda ro: ro[1].support not in ids)]


def _kin(category: str) -> set[str]:
    """The category and its catalog siblings ("cup": mug, glass, bottle: drinkware)."""
    from wana.assets import vocabulary

    info = vocabulary.CATEGORIES.get(category)
    if info is None or not info.parent:
        return {category}
    return {category} | {n for n, i in vocabulary.CATEGORIES.items() if i.parent == info.parent}


def _one_each(
    g: SentenceGraph, sid: str, scene: Scene, wanted: Sequence[Need], last_at: dict[str, list[str]]
) -> list[Need]:
    """One more object for each character beyond the first few of a sentence whose characters all do one
    held action with no object of their own ("They drink" with three at the table and one glass): each
    holds one, of the kind the room already has ("glasses" on the table: a glass) else the action's own."""
    doers: dict[str, list[str]] = {}
    verbs: dict[str, str] = {}
    for c in g.characters:
        for a in c.actions:
            refs = [r for r in (a.target, a.instrument, a.destination) if r]
            named = [find_object(scene, r) for r in refs]
            if a.action in DEFAULT_PROP and clip_kind(a) == "handheld" and not any(named):
                doers.setdefault(a.action, []).append(c.name)
                verbs.setdefault(a.action, a.verb or a.action.replace("_", " "))
    out = []
    for action, names in doers.items():
        if len(names) < 2 or not _known(DEFAULT_PROP[action]):
            continue
        kin = _kin(DEFAULT_PROP[action])
        # what the room has for it: cups and glasses, not the bottle poured from (a drink is poured out of it)
        have = [o for o in _usable(scene, action) if o.category in kin and o.category not in POURED_FROM]
        have_ids = {o.id for o in have}
        added = sum(1 for n in wanted if n.sentence_id == sid and n.node.category in kin)
        category = have[0].category if have else DEFAULT_PROP[action]
        count = len(have) + added
        held = f"{count} {category.replace('_', ' ')}" + ("" if count == 1 else "s")
        short = names[count:]
        # One each in the room is not one each in reach: glasses in the middle of the table stand 1.1 m
        # from a chair (a seated drinker reaches 0.9 m). As many as there are drinkers go to the places of
        # the table they sit at that have none in reach, until as many places as drinkers have one.
        bare, places = _bare_places(scene, names, last_at, kin)
        for i in range(max(len(short), min(len(bare), len(names) - (places - len(bare))))):
            node = ObjectNode(id=category, category=category, word=category.replace("_", " "))
            if i < len(short):
                near = tuple(
                    dict.fromkeys(r for r in reversed(last_at.get(short[i], [])) if r not in have_ids)
                )
                why = f"{len(names)} characters {verbs[action]} and the room has {held}"
                out.append(Need(node, sid, near, action, why, short[i]))
                continue
            table = bare[i][0]
            why = (
                f"{len(names)} characters {verbs[action]} at the {table.split('#')[0].replace('_', ' ')} and "
                f"a place there has no {category.replace('_', ' ')} in reach"
            )
            out.append(Need(node, sid, (table,), action, why))
    return out


def _bare_places(
    scene: Scene, names: Sequence[str], last_at: dict[str, list[str]], kin: set[str]
) -> tuple[list[tuple[str, np.ndarray]], int]:
    """(table id, sitting point xz) of each place at the table the characters last went to ("sit at the
    table") with nothing of the kin in a seated person's reach (PLACE_REACH), one per seat; and how many
    places that table has."""
    tables = []
    for n in names:  # each one's latest object with a table top ("sits at the table", then "pours")
        tops = [o for r in reversed(last_at.get(n, [])) if (o := find_object(scene, r)) and table_tops(o)]
        tables += tops[:1]
    mine = [
        np.array([o.position[0], o.position[2]])
        for o in scene.objects
        if o.category in kin and o.category not in POURED_FROM
    ]
    out, seen = [], set()
    for table in {t.id: t for t in tables}.values():
        for seat, xz in _seats_at(scene, table):
            if seat in seen:
                continue
            seen.add(seat)
            if not any(np.linalg.norm(m - xz) <= PLACE_REACH for m in mine):
                out.append((table.id, xz))
    return out, len(seen)


def table_tops(placed: PlacedObject) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(height, xz min, xz max) of an object's support surfaces at table height, world; none for a seat or a
    bed (a cup is not put where someone sits)."""
    try:
        if any(n.startswith(("sit", "lie")) for n in _catalog().asset_for(placed).contact_points):
            return []
        surfs = _catalog().world_support_surfaces(placed)
    except Exception:  # noqa: BLE001 - unknown category: nothing to put on
        return []
    return [
        (h, corners.min(axis=0), corners.max(axis=0))
        for h, corners in surfs
        if TABLE_HEIGHT[0] <= h <= TABLE_HEIGHT[1]
    ]


def footprint(category: str, attributes: dict[str, str], seed: int) -> np.ndarray:
    """(2, 2) xz half extents box of a catalog object (min, max), object frame."""
    obj = _catalog().make_object(category, attributes, seed)
    b = np.asarray(obj.collision_boxes, float).reshape(-1, 2, 3)
    return np.stack([b[:, 0, [0, 2]].min(axis=0), b[:, 1, [0, 2]].max(axis=0)])


def _boxes_xz(scene: Scene, ids: set[str] | None = None) -> list[tuple[np.ndarray, float, float]]:
    """(xz min/max (2, 2), bottom, top) of the objects (all when ids is None), world."""
    out = []
    for o in scene.objects:
        if ids is not None and o.id not in ids:
            continue
        try:
            b = np.asarray(_catalog().world_bounds(o), float)
        except Exception:  # noqa: BLE001
            continue
        out.append((b[:, [0, 2]], float(b[0, 1]), float(b[1, 1])))
    return out


def _overlaps(
    lo: np.ndarray, hi: np.ndarray, y0: float, y1: float, boxes: list[tuple[np.ndarray, float, float]]
) -> bool:
    """Whether the box [lo, hi] x [y0, y1] comes within GAP of any of the boxes (xz min/max, bottom, top)."""
    return any(
        np.all(lo < b[1] + GAP) and np.all(hi > b[0] - GAP) and y0 < top and y1 > bottom
        for b, bottom, top in boxes
    )


def _seats_at(scene: Scene, anchor: PlacedObject, reach: float = SEAT_REACH) -> list[tuple[str, np.ndarray]]:
    """(id, xz) of the seats whose sitting point is within ``reach`` of the anchor's table top, by id."""
    tops = table_tops(anchor)
    out = []
    for o in scene.objects:
        if o.id == anchor.id:
            continue
        try:
            points = _catalog().asset_for(o).contact_points
            sit = [np.asarray(cp.position, float) for n, cp in points.items() if n.startswith("sit")]
            if not sit:
                continue
            xz = _catalog().to_world(o, np.stack(sit))[:, [0, 2]]
        except Exception:  # noqa: BLE001 - unknown category
            continue
        for p in xz:
            if any(np.linalg.norm(np.clip(p, lo, hi) - p) <= reach for _, lo, hi in tops):
                out.append((o.id, p))
    return sorted(out, key=lambda t: (t[0], float(t[1][0]), float(t[1][1])))


def _before_seat(
    scene: Scene, anchor: PlacedObject, need: Need, fp: np.ndarray, height: float
) -> tuple | None:
    """(x, y, z) of a free spot on the anchor in front of a seat with nothing of the need's kind in reach
    yet ("They drink" at the table: a glass at each place), or None."""
    kin = _kin(need.node.category)
    mine = [
        np.array([o.position[0], o.position[2]])
        for o in scene.objects
        if o.category in kin and o.category not in POURED_FROM
    ]
    for _, seat in _seats_at(scene, anchor):
        if any(np.linalg.norm(m - seat) <= PLACE_REACH for m in mine):
            continue
        spot = on_surface(scene, anchor, fp, height, toward=seat)
        if spot is not None and np.hypot(spot[0] - seat[0], spot[2] - seat[1]) <= PLACE_REACH:
            return spot
    return None


def on_surface(
    scene: Scene, anchor: PlacedObject, fp: np.ndarray, height: float, toward: np.ndarray | None = None
) -> tuple | None:
    """(x, y, z) centre of the base of a free spot on the anchor's surfaces nearest their middle (nearest
    ``toward``, xz, when given), or None."""
    others = _boxes_xz(scene)
    for h, lo, hi in sorted(table_tops(anchor), key=lambda s: -float(np.prod(s[2] - s[1]))):
        size = fp[1] - fp[0]
        if np.any(hi - lo < size + 2 * EDGE):
            lo, hi = lo - EDGE, hi + EDGE  # a small surface: the object may come to its edge
            if np.any(hi - lo < size + 2 * EDGE):
                continue
        xs = np.linspace(lo[0] + EDGE - fp[0][0], hi[0] - EDGE - fp[1][0], 9)
        zs = np.linspace(lo[1] + EDGE - fp[0][1], hi[1] - EDGE - fp[1][1], 9)
        # Nearest the room's middle first: the front of a counter against a wall, within a person's reach.
        aim = np.zeros(2) if toward is None else toward
        spots = sorted(((x, z) for x in xs for z in zs), key=lambda p: np.hypot(p[0] - aim[0], p[1] - aim[1]))
        for x, z in spots:
            a, b = np.array([x, z]) + fp[0], np.array([x, z]) + fp[1]
            if not _overlaps(a, b, h + 0.005, h + height, others):
                return (float(x), float(h), float(z))
    return None


def _at_work_point(anchor: PlacedObject, need: Need) -> tuple | None:
    """(x, y, z) of the anchor's own point of the need's action, for a named anchor with no room on top
    ("washes the dishes in the sink": the dishes lie in the basin, where the hands wash), else None."""
    if not need.action or anchor.id not in need.near:
        return None
    meant = {need.action, need.action.split("_")[0]} - {"touch", "pick_up"}
    try:
        points = _catalog().asset_for(anchor).contact_points
        name = next((n for n in points if n in meant), None)
        if name is None:
            return None
        cp = points[name]
        hands = np.asarray([cp.position, *cp.extra.values()], float)  # between the two hands
        x, y, z = _catalog().to_world(anchor, hands.mean(axis=0, keepdims=True))[0]
    except Exception:  # noqa: BLE001 - unknown category: no point to put it at
        return None
    return float(x), float(y), float(z)


def _beside(scene: Scene, anchor: PlacedObject | None, fp: np.ndarray, height: float) -> tuple | None:
    """(x, 0, z) of a free floor spot beside the anchor (the room's middle without one), inside the walls."""
    others = _boxes_xz(scene)
    room = scene.room
    if anchor is not None:
        b = np.asarray(_catalog().world_bounds(anchor), float)[:, [0, 2]]
    else:
        b = np.zeros((2, 2))
    centre = (b[0] + b[1]) / 2
    for ring in FLOOR_RING:
        for ang in np.linspace(0, 2 * np.pi, 16, endpoint=False):
            d = np.array([np.sin(ang), np.cos(ang)])
            half = (b[1] - b[0]) / 2
            p = centre + d * (np.abs(d) @ half + ring)
            a, c = p + fp[0], p + fp[1]
            inside = (
                abs(p[0]) + fp[1][0] < room.width / 2 - 0.1 and abs(p[1]) + fp[1][1] < room.depth / 2 - 0.1
            )
            if inside and not _overlaps(a, c, 0.0, height, others):
                return (float(p[0]), 0.0, float(p[1]))
    return None


def _tables(scene: Scene) -> list[PlacedObject]:
    """Floor objects with a surface at table height, largest surface first."""
    scored = []
    for o in scene.objects:
        surfs = table_tops(o) if not o.support else []
        if surfs:
            scored.append((max(float(np.prod(s[2] - s[1])) for s in surfs), o))
    return [o for _, o in sorted(scored, key=lambda t: -t[0])]


def place(scene: Scene, need: Need, seed: int = 0) -> tuple[PlacedObject, str] | None:
    """The object of one need placed in the room and the id it rests on or stands by ("" when neither)."""
    node = need.node
    attrs = dict(node.attributes)
    try:
        obj = _catalog().make_object(node.category, attrs, seed)
    except Exception:  # noqa: BLE001 - no mesh for it: it cannot be shown
        return None
    boxes = np.asarray(obj.collision_boxes, float).reshape(-1, 2, 3)
    fp = np.stack([boxes[:, 0, [0, 2]].min(axis=0), boxes[:, 1, [0, 2]].max(axis=0)])
    height = float(boxes[:, 1, 1].max())
    by_id = {o.id: o for o in scene.objects}
    anchors = [by_id[r] if r in by_id else find_object(scene, r) for r in need.near]
    found = [o for o in [*anchors, *_tables(scene)] if o is not None]
    candidates = list({o.id: o for o in found}.values())  # by id, the first kept
    if _mount(node.category) == "surface":
        if need.why:  # one each: in front of a place at the table that has none
            for anchor in candidates:
                spot = _before_seat(scene, anchor, need, fp, height)
                if spot is not None:
                    return _placed(node, attrs, seed, spot, anchor.id), anchor.id
        for anchor in candidates:
            spot = on_surface(scene, anchor, fp, height) or _at_work_point(anchor, need)
            if spot is not None:
                return _placed(node, attrs, seed, spot, anchor.id), anchor.id
        if not need.holder:
            return None
        # nothing to rest it on (a gallery has no table): the one who uses it brings it (carried), so it
        # stands in for a thing taken from a pocket; its place on the floor is never seen
    beside: list[PlacedObject | None] = [*candidates, None]
    for near in beside:
        spot = _beside(scene, near, fp, height)
        if spot is not None:
            return _placed(node, attrs, seed, spot, ""), near.id if near is not None else ""
    return None


def free_id(scene: Scene, wanted: str) -> str:
    """``wanted``, or "<wanted>/<k>" with the first k no object of the room has (ids are unique: the story
    checks and the planner look objects up by them)."""
    ids = {o.id for o in scene.objects}
    if wanted not in ids:
        return wanted
    k = 2
    while f"{wanted}/{k}" in ids:
        k += 1
    return f"{wanted}/{k}"


def aimed(
    characters: dict[str, tuple[CharacterNode, list[str]]], scene: Scene
) -> dict[str, tuple[CharacterNode, list[str]]]:
    """Held actions that name no object, aimed at what the same sentence walked to when that offers the
    action's own point: "Anna walks to the microphone and sings" sings into the microphone on its stand
    (the planner's reach to its "sing" point), not into an empty hand beside it."""
    out = {}
    for name, (node, sids) in characters.items():
        actions = list(node.actions)
        for k in range(1, len(actions)):
            a, before = actions[k], actions[k - 1]
            if a.target or a.instrument or a.destination or sids[k] != sids[k - 1]:
                continue
            if clip_kind(a) not in HELD_KINDS or not _is_walk(before):
                continue
            there = find_object(scene, before.destination or before.target)
            if there is not None and offers(there, a.action):
                actions[k] = msgspec.structs.replace(a, destination=there.id)
        out[name] = (msgspec.structs.replace(node, actions=actions), sids)
    return out


PUTS = ("put_down",)  # actions that set down what the hand holds


def carried(
    characters: dict[str, tuple[CharacterNode, list[str]]],
    scene: Scene,
    added: set[str],
    texts: Mapping[str, str] | None = None,
) -> tuple[dict[str, tuple[CharacterNode, list[str]]], dict[str, str]]:
    """The characters who bring an added object with them, and each one's actions put it where the sentence
    says: "She puts her bag on the teacher's desk" in a room with no bag (provide added one on the desk)
    has Ms Lee hold the bag from her first frame (she came in with it), so the put moves it from her hand to
    the desk. An object is brought by the character whose first action on it puts it down; that put gets
    the surface it was added on as its destination when the parse named none. A held object is brought too
    when it is the character's own ("calls someone on his phone": not a phone 5 m away on another table) or
    when nothing could hold it (a camera in a gallery with no table: provide left it on the floor).

    Args:
        texts: sentence id -> its text, to read "his phone" (without it nothing is owned).

    Returns:
        (characters, name -> id of the object in the hand from the start).
    """
    out, holding = {}, {}
    taken: set[str] = set()
    for name, (node, sids) in characters.items():
        actions = list(node.actions)
        for k, a in enumerate(actions):
            placed = _added_used(scene, a, added)
            if placed is None or placed.id in taken:
                continue
            taken.add(placed.id)  # the first action on it decides (a "read" first: picked up where it lies)
            if name in holding or not holdable(placed):
                continue
            if a.action in PUTS:
                holding[name] = placed.id
                if not a.destination and placed.support:
                    actions[k] = msgspec.structs.replace(a, destination=placed.support)
            elif _in_hand(a, placed.id, placed.category) and (
                _unrested(placed) or owned((texts or {}).get(sids[k], ""), placed.category)
            ):
                holding[name] = placed.id
        out[name] = (msgspec.structs.replace(node, actions=actions), sids)
    return out, holding


def _added_used(scene: Scene, action: ActionNode, added: set[str]) -> PlacedObject | None:
    """The added object an action works with: the one it names, else (a held action) the one added for it
    ("takes a photo of the sculpture": the camera)."""
    ref = action.target or action.instrument
    placed = find_object(scene, ref) if ref else None
    if placed is not None and placed.id in added:
        return placed
    if placed is not None and action.target and action.instrument:
        other = find_object(scene, action.instrument)
        if other is not None and other.id in added:
            return other
    default = DEFAULT_PROP.get(action.action, "")
    if not default or clip_kind(action) not in HELD_KINDS:
        return None
    return next((o for o in scene.objects if o.id in added and o.category == default), None)


def _in_hand(action: ActionNode, ref: str, category: str) -> bool:
    """Whether the object an action names is the one in its hand: any of a handheld action's but what it
    pours into, a tool action's tool only ("saws the plank": the saw, not the plank)."""
    kind = clip_kind(action)
    if kind == "handheld":
        return ref != action.destination
    return kind == "tool" and (ref == action.instrument or category == DEFAULT_PROP.get(action.action))


def _unrested(placed: PlacedObject) -> bool:
    """A small object left on the floor because nothing in the room could hold it."""
    return not placed.support and _mount(placed.category) == "surface"


def owned(text: str, category: str) -> bool:
    """Whether a sentence names a thing of the category as someone's own ("his phone", "her old book")."""
    from wana.assets import vocabulary

    info = vocabulary.CATEGORIES.get(category)
    words = {category.replace("_", " "), *(info.synonyms if info is not None else ())}
    alternatives = "|".join(re.escape(w) for w in sorted(words, key=len, reverse=True))
    pattern = rf"\b(?:his|her|their|my|your|our)\s+(?:(?!(?:a|an|the|some)\s)[a-z]+\s+)?(?:{alternatives})\b"
    return re.search(pattern, text.lower()) is not None


def brought_notes(
    characters: dict[str, tuple[CharacterNode, list[str]]],
    holding: dict[str, str],
    scene: Scene,
    sentences: Sequence[Sentence],
) -> list[tuple[str, Diagnostic]]:
    """One I202 per object a character brings (carried), on the sentence that puts it down."""
    spans = {s.id: Span(s.start, s.end) for s in sentences}
    out = []
    for name, held in holding.items():
        node, sids = characters[name]
        placed = find_object(scene, held)
        # the first action that uses it: the put that sets it down, or a held action ("on his phone")
        k = next((k for k, a in enumerate(node.actions) if _added_used(scene, a, {held})), None)
        if placed is None or k is None:
            continue
        what = placed.category.replace("_", " ")
        put = node.actions[k].action in PUTS
        on = node.actions[k].destination.split("#")[0].replace("_", " ") if put else ""
        message = f"{name} brings the {what}: in the hand from {name}'s first frame" + (
            f", then put on the {on}" if on else ""
        )
        span = spans.get(sids[k], Span(0, 0))
        out.append((sids[k], Diagnostic(code="I202", message=message, span=span, severity="info")))
    return out


def _is_walk(action: ActionNode) -> bool:
    try:
        clip = get_clip(action.action) if action.action else None
    except KeyError:
        return False
    return clip is not None and "locomotion" in clip.tags


def offers(placed: PlacedObject, action: str) -> bool:
    """Whether an object has a contact point for the action itself (its name or first word)."""
    try:
        points = set(_catalog().asset_for(placed).contact_points)
    except Exception:  # noqa: BLE001 - unknown category
        return False
    return bool(({action, action.split("_")[0]} - {"touch", "pick_up"}) & points)


def _placed(
    node: ObjectNode, attrs: dict[str, str], seed: int, spot: tuple[float, float, float], support: str
) -> PlacedObject:
    return PlacedObject(
        id=node.id,
        category=node.category,
        attributes=attrs,
        seed=seed,
        position=(round(spot[0], 5), round(spot[1], 5), round(spot[2], 5)),
        yaw=0.0,
        support=support,
        from_text=True,
    )


def provide(
    scene: Scene, graphs: Sequence[SentenceGraph], sentences: Sequence[Sentence], seed: int = 0
) -> tuple[Scene, list[tuple[str, Diagnostic]]]:
    """The room with every object the actions use and the room lacked, and one I202 per object added."""
    needs = prop_needs(graphs, [s.id for s in sentences], scene)
    if not needs:
        return scene, []
    spans = {s.id: Span(s.start, s.end) for s in sentences}
    objects = list(scene.objects)
    notes = []
    for need in needs:
        now = Scene(room=scene.room, objects=objects, seed=scene.seed)
        got = place(now, need, seed)
        what = need.node.word or need.node.category.replace("_", " ")
        if got is None:
            continue
        placed, at = got
        placed = msgspec.structs.replace(placed, id=free_id(now, placed.id))
        objects.append(placed)
        where = (
            f"on the {at.split('#')[0].replace('_', ' ')}"
            if placed.support
            else f"with {need.holder}, nothing in the room to rest it on"
            if need.holder and _unrested(placed)
            else f"beside the {at.split('#')[0].replace('_', ' ')}"
            if at
            else "in the room"
        )
        why = need.why or f"the story uses the {what} but no scene sentence puts it in the room"
        owner = f" for {need.owner}" if need.owner else ""
        message = f"added a {placed.category.replace('_', ' ')} {where}{owner}: {why}"
        notes.append(
            (
                need.sentence_id,
                Diagnostic(
                    code="I202",
                    message=message,
                    span=spans.get(need.sentence_id, Span(0, 0)),
                    severity="info",
                ),
            )
        )
    return Scene(room=scene.room, objects=objects, seed=scene.seed), notes


__all__ = [
    "DEFAULT_PROP",
    "PUTS",
    "Need",
    "aimed",
    "carried",
    "free_id",
    "made_for",
    "place",
    "prop_needs",
    "provide",
    "worked_at",
]
