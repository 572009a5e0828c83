"""The action library: authored keyframe clips in assets/actions/*.json plus imported ones.

Each clip file holds its metadata (tags, synonyms, duration, looping, body parts, contact joints,
the object interaction it needs) and sparse keyframes: per key a time, an easing for the stretch
that arrives at it, Euler angles in degrees (order "ZYX", intrinsic, as BVH) for the joints it
poses, and an optional root offset (metres, character frame: x left, y up, z forward) and root yaw.
Joints a key does not name take the neutral standing pose. New clips are data: drop a file in
assets/actions/ (or run `wana motion import FILE.bvh`) and no model needs retraining.

Rebuild the authored files with `python -m tools.authoring.author_actions`.
"""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from wana.domain import quat
from wana.domain.clip_headers import ACTIONS_DIR, clip_headers, library_dirs, library_key
from wana.domain.clip_headers import IMPORTED_DIR as IMPORTED_DIR  # re-exported: services/motion/cli.py
from wana.domain.posing import neutral
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS
from wana.domain.units import FPS

EULER_ORDER = "ZYX"

BODY_PARTS = ("full_body", "upper_body", "lower_body", "left_arm", "right_arm", "spine", "head", "legs")
EASINGS = ("linear", "in", "out", "in_out", "step")


@dataclass(frozen=True)
class Keyframe:
    """One key: time in seconds, easing of the stretch arriving here, local rotations of named joints."""

    t: float
    ease: str
    rotations: dict[str, np.ndarray]  # joint -> (4,) quaternion x, y, z, w
    root: tuple[float, float, float] = (0.0, 0.0, 0.0)  # metres, character frame (x left, y up, z fwd)
    root_yaw: float = 0.0  # degrees about +Y, > 0 turns left


@dataclass(frozen=True)
class Interaction:
    """What a clip needs from its target object."""

    object: str  # kind of object point it needs: "seat", "keyboard", "handheld", "surface", "person", ...
    contacts: tuple[str, ...]  # canonical joints brought to the object's contact points
    window: tuple[float, float]  # seconds of the clip during which the contacts hold


@dataclass(frozen=True)
class ActionClip:
    name: str
    tags: tuple[str, ...]
    synonyms: tuple[str, ...]
    duration_s: float
    looping: bool
    body_parts: tuple[str, ...]
    contact_joints: tuple[str, ...]
    interaction: Interaction | None
    keyframes: tuple[Keyframe, ...] = field(repr=False, default=())
    source: str = "authored"  # "authored" | "imported"

    @property
    def drives_lower_body(self) -> bool:
        return any(p in ("full_body", "lower_body", "legs") for p in self.body_parts)

    def sample(
        self, fps: int = FPS, duration_s: float | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Evaluate the clip at fps.

        Args:
            fps: frames per second.
            duration_s: wanted length; looping clips repeat, others hold their last key (None = natural).

        Returns:
            rotations (T, J, 4), root offsets (T, 3) in the character frame, root yaw (T,) radians.
        """
        rot, root, yaw = _sample_cached(
            self, fps, round(self.duration_s if duration_s is None else duration_s, 4)
        )
        return rot.copy(), root.copy(), yaw.copy()


def _ease(u: np.ndarray, kind: str) -> np.ndarray:
    if kind == "in":
        return u * u
    if kind == "out":
        return 1.0 - (1.0 - u) ** 2
    if kind == "in_out":
        return u * u * (3.0 - 2.0 * u)
    if kind == "step":
        return (u >= 1.0).astype(np.float64)
    return u


@functools.lru_cache(maxsize=1)
def neutral_rotations() -> np.ndarray:
    """(J, 4) the neutral standing pose every clip starts from."""
    rot = quat.identity((N_JOINTS,))
    for name, q in neutral().items():
        rot[JOINT_INDEX[name]] = q
    return rot


def _key_arrays(clip: ActionClip) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    base = neutral_rotations()
    times = np.array([k.t for k in clip.keyframes])
    rots = np.repeat(base[None], len(clip.keyframes), axis=0)
    for i, k in enumerate(clip.keyframes):
        for name, q in k.rotations.items():
            rots[i, JOINT_INDEX[name]] = q
    roots = np.array([k.root for k in clip.keyframes], dtype=np.float64)
    yaws = np.radians([k.root_yaw for k in clip.keyframes])
    return times, rots, roots, yaws


_SAMPLED: dict[tuple[str, int, float], tuple[ActionClip, tuple[np.ndarray, np.ndarray, np.ndarray]]] = {}


def _sample_cached(
    clip: ActionClip, fps: int, duration_s: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sampled clips are reused across segments and requests (clips are immutable; callers get copies).

    Keyed by name, fps and duration; an entry counts only for the very clip object it was made
    from, so a reloaded or re-imported clip is sampled afresh.
    """
    key = (clip.name, fps, duration_s)
    hit = _SAMPLED.get(key)
    if hit is not None and hit[0] is clip:
        return hit[1]
    if len(_SAMPLED) > 1024:
        _SAMPLED.clear()
    out = _sample(clip, fps, duration_s)
    _SAMPLED[key] = (clip, out)
    return out


def _sample(clip: ActionClip, fps: int, duration_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    times, rots, roots, yaws = _key_arrays(clip)
    n = max(1, int(round(duration_s * fps)))
    t = np.arange(n) / fps
    if clip.looping and clip.duration_s > 0:
        cycles = np.floor(t / clip.duration_s)
        local = t - cycles * clip.duration_s
    else:
        cycles = np.zeros(n)
        local = np.minimum(t, times[-1])
    idx = (
        np.clip(np.searchsorted(times, local, side="right"), 1, len(times) - 1)
        if len(times) > 1
        else np.zeros(n, int)
    )
    if len(times) == 1:
        return np.repeat(rots[:1], n, 0), np.repeat(roots[:1], n, 0), np.repeat(yaws[:1], n)
    t0, t1 = times[idx - 1], times[idx]
    u = np.clip((local - t0) / np.maximum(t1 - t0, 1e-9), 0.0, 1.0)
    eases = [clip.keyframes[i].ease for i in idx]
    for kind in set(eases):
        m = np.array([e == kind for e in eases])
        u[m] = _ease(u[m], kind)
    out_rot = quat.slerp(rots[idx - 1], rots[idx], u[:, None])
    out_root = roots[idx - 1] + (roots[idx] - roots[idx - 1]) * u[:, None]
    out_yaw = yaws[idx - 1] + (yaws[idx] - yaws[idx - 1]) * u
    if clip.looping:  # a looping clip that travels (e.g. a turn cycle) accumulates per cycle
        out_root = out_root + cycles[:, None] * (roots[-1] - roots[0])
        out_yaw = out_yaw + cycles * (yaws[-1] - yaws[0])
    return out_rot, out_root, out_yaw


def clip_from_dict(d: dict, source: str = "authored") -> ActionClip:
    """Build a clip from its JSON form; raises ValueError naming the problem."""
    try:
        name = str(d["name"])
        order = d.get("euler", EULER_ORDER)
        keys = []
        posed = [(joint, angles) for k in d["keys"] for joint, angles in k.get("pose", {}).items()]
        for joint, _ in posed:
            if joint not in JOINT_INDEX:
                raise ValueError(f"clip {name!r}: unknown joint {joint!r}")
        # every key's angles in one call (a clip has ~90 of them: one call each cost most of the load)
        turns = iter(
            quat.from_euler(order, np.asarray([a for _, a in posed], dtype=np.float64).reshape(-1, 3))
        )
        for k in d["keys"]:
            rotations = {joint: next(turns).copy() for joint in k.get("pose", {})}
            ease = k.get("ease", "in_out")
            if ease not in EASINGS:
                raise ValueError(f"clip {name!r}: unknown easing {ease!r}")
            keys.append(
                Keyframe(
                    t=float(k["t"]),
                    ease=ease,
                    rotations=rotations,
                    root=tuple(float(x) for x in k.get("root", (0, 0, 0))),  # type: ignore[arg-type]
                    root_yaw=float(k.get("root_yaw", 0.0)),
                )
            )
        if not keys:
            raise ValueError(f"clip {name!r} has no keys")
        times = [k.t for k in keys]
        if any(b < a for a, b in zip(times, times[1:], strict=False)):
            raise ValueError(f"clip {name!r}: key times must not decrease")
        inter = d.get("interaction")
        interaction = None
        if inter:
            interaction = Interaction(
                object=str(inter["object"]),
                contacts=tuple(inter.get("contacts", ())),
                window=tuple(inter.get("window", (0.0, float(d["duration_s"])))),
            )  # type: ignore[arg-type]
        parts = tuple(d.get("body_parts", ("upper_body",)))
        for p in parts:
            if p not in BODY_PARTS:
                raise ValueError(f"clip {name!r}: unknown body part {p!r}")
        return ActionClip(
            name=name,
            tags=tuple(d.get("tags", ())),
            synonyms=tuple(d.get("synonyms", ())),
            duration_s=float(d["duration_s"]),
            looping=bool(d.get("looping", False)),
            body_parts=parts,
            contact_joints=tuple(d.get("contact_joints", ())),
            interaction=interaction,
            keyframes=tuple(keys),
            source=d.get("source", source),
        )
    except KeyError as exc:
        raise ValueError(f"clip file is missing field {exc}") from exc


@functools.lru_cache(maxsize=4)
def _load(dirs: tuple[Path, ...]) -> dict[str, ActionClip]:
    clips: dict[str, ActionClip] = {}
    for directory in dirs:
        if not directory.is_dir():
            continue
        for path in sorted(directory.glob("*.json")):
            if path.name.startswith("_"):
                continue
            clip = clip_from_dict(
                json.loads(path.read_text()), source="imported" if directory != ACTIONS_DIR else "authored"
            )
            clips[clip.name] = clip
    return clips


def load_library() -> dict[str, ActionClip]:
    """All clips by name (authored, then imported, then $WANA_ACTIONS_DIR; later ones win)."""
    return dict(_load(tuple(library_dirs())))


def reload_library() -> dict[str, ActionClip]:
    """Forget the cache (after an import) and load again."""
    _load.cache_clear()
    _synonyms.cache_clear()
    clip_headers.cache_clear()  # type: ignore[attr-defined]
    return load_library()


def action_names() -> list[str]:
    """Sorted names of every action in the library."""
    return sorted(load_library())


def synonym_index() -> dict[str, str]:
    """Lower-case phrase (name with spaces, or synonym) -> action name."""
    return dict(_synonyms(tuple(library_dirs())))


@functools.lru_cache(maxsize=4)
def _synonyms(dirs: tuple[Path, ...]) -> dict[str, str]:
    """synonym_index, built once per library load (get_clip asks it for every name that is not a clip)."""
    out: dict[str, str] = {}
    for clip in _load(dirs).values():
        out.setdefault(clip.name.replace("_", " "), clip.name)
        for s in clip.synonyms:
            out.setdefault(s.lower(), clip.name)
    return out


def get_clip(name: str) -> ActionClip:
    """The clip called name; raises KeyError listing close names when unknown."""
    dirs = library_key()
    lib = _load(dirs)  # the cached table itself: get_clip runs for every segment of every motion
    if name in lib:
        return lib[name]
    alias = _synonyms(dirs).get(name.replace("_", " ").lower())
    if alias:
        return lib[alias]
    raise KeyError(f"unknown action {name!r}")


_NAME_FILLERS = frozenset(
    {"with", "on", "at", "to", "in", "of", "up", "down", "off", "out", "and", "the", "a"}
)


def names_object(action: str, category: str) -> bool:
    """Whether an action's clip name names a kind of object after its verb, the category's head noun
    ("text_on_phone", "pick_up_phone_answer": a phone; "play_guitar": an electric guitar; not "take_photo"
    for a photo frame). Such an object is made for the action though the catalog names no point for it:
    the phone's one held point is "call", and "texts" or "answers the phone" hold it there too."""
    words = [w for w in action.lower().split("_")[1:] if w not in _NAME_FILLERS]
    head = category.lower().split("_")[-1]
    return bool(head) and head in words


# Frames a synthesised piece blends from its start state's rest pose and into its end state's (both
# ends), so pieces made apart meet without a pose pop; contacts hold only between them.
JOIN_FRAMES = 10

# Catalog contact-point names (wana.assets.catalog make_object(cat).contact_points) preferred for each
# interaction kind, best first; CLIP_POINTS comes before them for the clips that mean one point.
PREFERRED_POINTS = {
    "seat": ("sit", "sit_0"),
    "bed": ("lie", "sit"),
    "keyboard": ("type", "click", "use", "work", "write", "touch"),
    "instrument": ("play", "work", "touch"),
    "surface": ("write", "work", "eat", "cook", "wash", "touch"),
    "button": ("switch", "use", "touch"),
    "door": ("open", "touch"),
    "container": ("open", "take", "touch", "pick_up"),
    "tool": ("work", "saw", "hammer", "drill", "screw", "cut", "touch"),
    "bag": ("punch", "touch"),
    "floor_item": ("pick_up", "lift", "carry", "touch"),
}
CLIP_POINTS = {
    "type": ("type",),
    "use_mouse": ("click", "use", "type"),
    "play_piano": ("play",),
    "play_drums": ("play",),
    "punch_bag": ("punch",),
    "write": ("write",),
    "write_on_blackboard": ("write",),
    "draw": ("write", "paint"),
    "paint": ("paint", "write"),
    "eat": ("eat",),
    "cook": ("cook",),
    "chop": ("cook", "cut", "work"),
    "wash_dishes": ("wash",),
    "wash_hands": ("wash",),
    "iron": ("work", "write"),
    "fold_clothes": ("work", "write"),
    "wipe_table": ("touch",),
    "wipe_window": ("touch",),
    "lean_on_wall": ("touch",),
    "push": ("touch",),
    "pull": ("open", "touch"),
    "knock": ("touch",),
    "open_door": ("open",),
    "close_door": ("open",),
    "open_fridge": ("open",),
    "open_drawer": ("open",),
    "press_switch": ("switch", "use"),
    "push_button": ("use", "switch"),
    "saw": ("saw",),
    "hammer": ("hammer", "work"),
    "drill": ("drill", "work"),
    "screw": ("screw", "work"),
    "sweep": ("sweep",),
    "pick_up": ("pick_up", "lift"),
    "put_down": ("pick_up",),
    "lie_down": ("lie",),
    "sleep": ("lie",),
}


def contact_targets(
    clip: ActionClip, points: dict[str, list[tuple[str, np.ndarray]]]
) -> dict[str, tuple[float, float, float]]:
    """joint -> world target for the clip's contact joints, from the object's contact points."""
    if not clip.interaction or not points:
        return {}
    preferred = CLIP_POINTS.get(clip.name, ()) + PREFERRED_POINTS.get(clip.interaction.object, ())
    names = list(dict.fromkeys([n for n in preferred if n in points] + sorted(points)))
    wanted = {
        _limb(j) for j in clip.interaction.contacts
    }  # a hand point serves a middle-finger contact and back
    for name in names:
        pairs = points[name]
        joints = {j for j, _ in pairs}
        if wanted & {_limb(j) for j in joints} or (
            clip.interaction.object in ("seat", "bed") and "Hips" in joints
        ):
            return {j: (float(p[0]), float(p[1]), float(p[2])) for j, p in pairs}
    return {}


def _limb(joint: str) -> str:
    return joint.replace("Middle1", "")


__all__ = [
    "CLIP_POINTS",
    "JOIN_FRAMES",
    "PREFERRED_POINTS",
    "contact_targets",
    "ActionClip",
    "Interaction",
    "Keyframe",
    "JOINT_NAMES",
    "action_names",
    "get_clip",
    "load_library",
    "names_object",
    "reload_library",
    "synonym_index",
    "neutral_rotations",
]
