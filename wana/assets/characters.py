"""Procedural characters on the canonical skeleton: skinned meshes with face blendshapes.

Each character has its own rest offsets (height, limb and shoulder proportions), a body made of
smooth parts rigidly attached to bones with blended weights near the joints (4 influences per
vertex), clothing/skin/hair colours as vertex colours, and a face whose eyes, brows and mouth carry
blendshapes for the expressions in ``EXPRESSIONS``. Rest pose: T-pose, feet on y = 0, facing +Z.

    >>> eve = make_character("Eve")
    >>> verts = pose_vertices(eve, identity_pose(1), eve.offsets[None, 0], {"smile": 1.0})
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from wana.assets.geometry import Part, _rotation_from_y
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS, PARENTS, REST_OFFSETS

# Face blendshape names, in the order of Motion.expression columns.
EXPRESSIONS: tuple[str, ...] = (
    "smile",
    "frown",
    "brows_up",
    "brows_down",
    "mouth_open",
    "eyes_closed",
    "squint",
    "pucker",
)


@dataclass(frozen=True)
class CharacterSpec:
    name: str
    height: float  # metres
    build: float  # width factor (shoulders, hips, limb girth)
    legs: float  # leg length factor relative to the torso
    skin: tuple[int, int, int]
    shirt: tuple[int, int, int]
    pants: tuple[int, int, int]
    hair: tuple[int, int, int]
    hair_style: str  # "short", "long", "bun", "bald"
    shoes: tuple[int, int, int] = (40, 35, 30)


SPECS: tuple[CharacterSpec, ...] = (
    CharacterSpec(
        "Eve", 1.68, 0.92, 1.02, (238, 200, 170), (200, 60, 70), (40, 50, 90), (90, 50, 25), "long"
    ),
    CharacterSpec(
        "Tom", 1.82, 1.08, 1.0, (225, 185, 150), (60, 110, 180), (60, 60, 65), (50, 35, 20), "short"
    ),
    CharacterSpec(
        "Mary", 1.62, 0.9, 0.98, (200, 150, 110), (120, 60, 160), (30, 30, 35), (25, 20, 18), "bun"
    ),
    CharacterSpec(
        "John", 1.78, 1.15, 0.97, (150, 100, 70), (240, 240, 235), (90, 70, 50), (20, 18, 15), "short"
    ),
    CharacterSpec(
        "Anna", 1.71, 0.88, 1.05, (245, 215, 190), (60, 150, 90), (200, 190, 170), (230, 200, 120), "long"
    ),
    CharacterSpec(
        "Sam", 1.58, 1.0, 0.95, (170, 120, 85), (240, 160, 40), (50, 60, 120), (40, 30, 25), "short"
    ),
    CharacterSpec(
        "Lily", 1.52, 0.86, 1.0, (235, 195, 165), (240, 140, 180), (90, 130, 200), (150, 70, 30), "bun"
    ),
    CharacterSpec(
        "Max", 1.9, 1.12, 1.04, (230, 190, 160), (40, 40, 45), (30, 60, 110), (140, 110, 80), "bald"
    ),
    CharacterSpec(
        "Nora", 1.66, 0.95, 1.0, (120, 80, 55), (30, 140, 140), (240, 240, 240), (15, 12, 10), "long"
    ),
    CharacterSpec(
        "Leo", 1.75, 1.0, 1.0, (210, 170, 130), (150, 40, 40), (70, 70, 75), (100, 60, 30), "short"
    ),
    CharacterSpec(
        "Zoe", 1.6, 0.92, 1.03, (250, 220, 200), (250, 220, 60), (60, 40, 90), (200, 80, 40), "long"
    ),
    CharacterSpec("Ben", 1.85, 1.05, 0.99, (95, 65, 45), (90, 160, 70), (45, 45, 50), (10, 10, 10), "short"),
)
_BY_NAME = {s.name.lower(): s for s in SPECS}


@dataclass(frozen=True)
class Character:
    """A skinned character mesh (arrays are float32/uint for an exact glTF round trip).

    Attributes:
        name: display name.
        height: metres.
        offsets: (J, 3) float32 rest offsets (canonical joint order, wana.domain.skeleton.JOINT_NAMES).
        vertices: (V, 3) float32 rest-pose positions, metres.
        faces: (F, 3) uint32.
        colours: (V, 4) uint8 vertex colours.
        joints: (V, 4) uint16 joint indices.
        weights: (V, 4) float32 skin weights (rows sum to 1).
        blendshapes: expression name -> (V, 3) float32 vertex offsets.
    """

    name: str
    height: float
    offsets: np.ndarray
    vertices: np.ndarray
    faces: np.ndarray
    colours: np.ndarray
    joints: np.ndarray
    weights: np.ndarray
    blendshapes: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return JOINT_NAMES

    def rest_joint_positions(self) -> np.ndarray:
        """(J, 3) global joint positions in the rest pose."""
        return rest_positions(self.offsets.astype(np.float64))


def character_names() -> list[str]:
    """Names of the built-in characters."""
    return [s.name for s in SPECS]


def rest_positions(offsets: np.ndarray) -> np.ndarray:
    pos = np.zeros((N_JOINTS, 3))
    for j in range(N_JOINTS):
        pos[j] = offsets[j] if PARENTS[j] < 0 else pos[PARENTS[j]] + offsets[j]
    return pos


def character_offsets(spec: CharacterSpec) -> np.ndarray:
    """(J, 3) rest offsets for a character: scaled by height, limbs by ``legs``, widths by ``build``."""
    off = REST_OFFSETS.copy()
    for name in ("LeftLeg", "LeftFoot", "RightLeg", "RightFoot"):
        off[JOINT_INDEX[name]] *= spec.legs
    for name in ("LeftShoulder", "RightShoulder", "LeftUpLeg", "RightUpLeg"):
        off[JOINT_INDEX[name], 0] *= spec.build
    for name in ("LeftArm", "RightArm"):
        off[JOINT_INDEX[name], 0] *= spec.build
    legs = -(
        off[JOINT_INDEX["LeftUpLeg"], 1]
        + off[JOINT_INDEX["LeftLeg"], 1]
        + off[JOINT_INDEX["LeftFoot"], 1]
        + off[JOINT_INDEX["LeftToeBase"], 1]
    )
    off[0] = (0.0, legs, 0.0)
    top = (
        rest_positions(off)[JOINT_INDEX["Head"], 1] + 0.19
    )  # crown (with hair) about 19 cm above the head joint
    return (off * (spec.height / top)).astype(np.float32)


@lru_cache(maxsize=32)
def make_character(name: str) -> Character:
    """Build a character by name (case-insensitive). Raises KeyError for an unknown name."""
    spec = _BY_NAME.get(name.lower())
    if spec is None:
        raise KeyError(f"unknown character {name!r}; known: {character_names()}")
    return _build(spec)


def character_for(name: str) -> Character:
    """The built-in character of that name; an unknown name gets a built-in look chosen by the sum of its
    letters (deterministic across processes, unlike hash()): what the renderer, the motion service and the
    story checks all play a story's character with."""
    try:
        return make_character(name)
    except KeyError:
        names = character_names()
        return make_character(names[sum(ord(c) for c in name) % len(names)])


class _Body:
    """Accumulates parts with their bone, segment and face group."""

    def __init__(self, pos: np.ndarray, scale: float) -> None:
        self.pos, self.s = pos, scale
        self.items: list[tuple[Part, int, np.ndarray, np.ndarray, str]] = []

    def limb(self, bone: str, a: np.ndarray, b: np.ndarray, r: float, colour, extend: float = 0.03) -> None:  # noqa: ANN001
        d = b - a
        length = float(np.linalg.norm(d))
        mid = (a + b) / 2
        rot = _rotation_from_y(d / length)
        radii = np.array([r, length / 2 + extend * self.s, r])
        self.items.append((Part("ellipsoid", radii, rot, mid, (*colour, 255)), JOINT_INDEX[bone], a, b, ""))

    def blob(self, bone: str, centre, radii, colour, group: str = "") -> None:  # noqa: ANN001
        c = np.asarray(centre, float)
        self.items.append(
            (
                Part("ellipsoid", np.asarray(radii, float) * self.s, np.eye(3), c, (*colour, 255)),
                JOINT_INDEX[bone],
                c,
                c,
                group,
            )
        )

    def block(self, bone: str, lo, hi, colour, group: str = "") -> None:  # noqa: ANN001
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        self.items.append(
            (
                Part("box", (hi - lo) / 2, np.eye(3), (lo + hi) / 2, (*colour, 255)),
                JOINT_INDEX[bone],
                (lo + hi) / 2,
                (lo + hi) / 2,
                group,
            )
        )


def _build(spec: CharacterSpec) -> Character:
    off = character_offsets(spec)
    P = rest_positions(off.astype(np.float64))
    s = spec.height / 1.75
    g = spec.build
    j = {n: P[i] for n, i in JOINT_INDEX.items()}
    B = _Body(P, s)
    shirt, pants, skin = spec.shirt, spec.pants, spec.skin
    # torso and hips
    B.blob("Hips", j["Hips"] + [0, 0.0 * s, 0], (0.17 * g, 0.12, 0.12), pants)
    B.blob("Spine", j["Spine"] + [0, 0.06 * s, 0], (0.16 * g, 0.11, 0.11), shirt)
    B.blob("Spine1", j["Spine1"] + [0, 0.07 * s, 0], (0.17 * g, 0.12, 0.12), shirt)
    B.blob("Spine2", j["Spine2"] + [0, 0.07 * s, 0], (0.2 * g, 0.12, 0.12), shirt)
    B.limb("Neck", j["Neck"], j["Head"], 0.05 * s, skin, extend=0.02)
    head_c = j["Head"] + np.array([0.0, 0.07 * s, 0.0])
    B.blob("Head", head_c, (0.085, 0.11, 0.1), skin)
    hair = spec.hair
    if spec.hair_style != "bald":
        B.blob("Head", head_c + [0, 0.035 * s, -0.015 * s], (0.09, 0.085, 0.095), hair)
    if spec.hair_style == "long":
        B.blob("Head", head_c + [0, -0.06 * s, -0.06 * s], (0.09, 0.13, 0.05), hair)
    if spec.hair_style == "bun":
        B.blob("Head", head_c + [0, 0.08 * s, -0.08 * s], (0.045, 0.045, 0.045), hair)
    # face: eyes, pupils, brows, nose, mouth (groups drive the blendshapes)
    fz = head_c[2] + 0.095 * s
    for side, sx in (("L", 1.0), ("R", -1.0)):
        ex = sx * 0.035 * s
        ey = head_c[1] + 0.015 * s
        B.blob("Head", (ex, ey, fz - 0.008 * s), (0.017, 0.011, 0.008), (250, 250, 250), f"eye{side}")
        B.blob("Head", (ex, ey, fz - 0.001 * s), (0.007, 0.007, 0.004), (35, 30, 30), f"eye{side}")
        B.block(
            "Head",
            (ex - 0.02 * s, ey + 0.02 * s, fz - 0.01 * s),
            (ex + 0.02 * s, ey + 0.027 * s, fz + 0.002 * s),
            hair if spec.hair_style != "bald" else (90, 70, 60),
            f"brow{side}",
        )
    B.blob("Head", (0.0, head_c[1] - 0.012 * s, fz + 0.002 * s), (0.012, 0.02, 0.015), skin)
    B.blob("Head", (0.0, head_c[1] - 0.05 * s, fz - 0.012 * s), (0.03, 0.008, 0.01), (170, 60, 60), "mouth")
    # arms, hands, fingers
    for side in ("Left", "Right"):
        B.limb(f"{side}Shoulder", j[f"{side}Shoulder"], j[f"{side}Arm"], 0.06 * s * g, shirt, extend=0.02)
        B.limb(f"{side}Arm", j[f"{side}Arm"], j[f"{side}ForeArm"], 0.05 * s * g, shirt)
        B.limb(f"{side}ForeArm", j[f"{side}ForeArm"], j[f"{side}Hand"], 0.04 * s * g, skin)
        B.limb(f"{side}Hand", j[f"{side}Hand"], j[f"{side}HandMiddle1"], 0.03 * s, skin, extend=0.01)
        tip = j[f"{side}HandMiddle1"] + (j[f"{side}HandMiddle1"] - j[f"{side}Hand"]) * 0.8
        B.limb(f"{side}HandMiddle1", j[f"{side}HandMiddle1"], tip, 0.018 * s, skin, extend=0.005)
        B.limb(f"{side}UpLeg", j[f"{side}UpLeg"], j[f"{side}Leg"], 0.075 * s * g, pants)
        B.limb(f"{side}Leg", j[f"{side}Leg"], j[f"{side}Foot"], 0.055 * s * g, pants)
        foot, toe = j[f"{side}Foot"], j[f"{side}ToeBase"]
        B.block(
            f"{side}Foot",
            (foot[0] - 0.045 * s, 0.0, foot[2] - 0.05 * s),
            (foot[0] + 0.045 * s, foot[1] + 0.03 * s, toe[2]),
            spec.shoes,
        )
        B.block(
            f"{side}ToeBase",
            (toe[0] - 0.045 * s, 0.0, toe[2]),
            (toe[0] + 0.045 * s, 0.05 * s, toe[2] + 0.06 * s),
            spec.shoes,
        )
    return _assemble(spec, off, B)


def _weights_for(
    points: np.ndarray, bone: int, a: np.ndarray, b: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Joint indices (N, 4) and weights (N, 4): own bone, blended with the parent near the segment start."""
    n = len(points)
    idx = np.zeros((n, 4), np.uint16)
    w = np.zeros((n, 4), np.float32)
    idx[:, 0] = bone
    parent = PARENTS[bone]
    seg = b - a
    length2 = float(seg @ seg)
    if parent < 0 or length2 < 1e-12:
        w[:, 0] = 1.0
        return idx, w
    t = np.clip((points - a) @ seg / length2, 0.0, 1.0)
    wp = 0.5 * np.clip(1.0 - t / 0.2, 0.0, 1.0)
    idx[:, 1] = parent
    w[:, 0] = 1.0 - wp
    w[:, 1] = wp
    return idx, w


def _assemble(spec: CharacterSpec, off: np.ndarray, B: _Body) -> Character:
    verts, faces, cols, jidx, wts, groups = [], [], [], [], [], []
    n = 0
    for part, bone, a, b, group in B.items:
        v, f = part.mesh()
        i, w = _weights_for(v, bone, a, b)
        verts.append(v)
        faces.append(f + n)
        cols.append(np.tile(np.array(part.colour, np.uint8), (len(v), 1)))
        jidx.append(i)
        wts.append(w)
        groups.extend([group] * len(v))
        n += len(v)
    V = np.concatenate(verts).astype(np.float32)
    G = np.array(groups)
    s = spec.height / 1.75
    shapes = {name: np.zeros_like(V) for name in EXPRESSIONS}
    mouth = G == "mouth"
    mc = V[mouth].mean(axis=0)
    mx = (V[mouth, 0] - mc[0]) / max(np.abs(V[mouth, 0] - mc[0]).max(), 1e-6)
    shapes["smile"][mouth, 1] = 0.012 * s * mx**2
    shapes["smile"][mouth, 0] = 0.006 * s * mx
    shapes["frown"][mouth, 1] = -0.01 * s * mx**2
    lower = mouth & (V[:, 1] < mc[1])
    shapes["mouth_open"][lower, 1] = -0.012 * s
    shapes["pucker"][mouth, 0] = -(V[mouth, 0] - mc[0]) * 0.45
    shapes["pucker"][mouth, 2] = 0.006 * s
    for side in ("L", "R"):
        brow = G == f"brow{side}"
        shapes["brows_up"][brow, 1] = 0.012 * s
        bx = V[brow, 0]
        inner = 1.0 - np.abs(bx) / max(np.abs(bx).max(), 1e-6)  # 1 at the inner end (towards the nose)
        shapes["brows_down"][brow, 1] = -0.004 * s - 0.008 * s * inner
        eye = G == f"eye{side}"
        cy = V[eye, 1].mean()
        shapes["eyes_closed"][eye, 1] = -(V[eye, 1] - cy) * 0.92
        shapes["squint"][eye, 1] = -(V[eye, 1] - cy) * 0.5
    W = np.concatenate(wts)
    W /= W.sum(axis=1, keepdims=True)
    return Character(
        name=spec.name,
        height=float(spec.height),
        offsets=off.astype(np.float32),
        vertices=V,
        faces=np.concatenate(faces).astype(np.uint32),
        colours=np.concatenate(cols),
        joints=np.concatenate(jidx),
        weights=W.astype(np.float32),
        blendshapes={k: v.astype(np.float32) for k, v in shapes.items()},
    )


def pose_vertices(
    character: Character,
    rotations: np.ndarray,
    root_position: np.ndarray,
    expression: dict[str, float] | np.ndarray | None = None,
) -> np.ndarray:
    """Linear blend skinning.

    Args:
        character: the character.
        rotations: (T, J, 4) local joint rotations (x, y, z, w).
        root_position: (T, 3) world Hips position.
        expression: blendshape weights by name, or an (len(EXPRESSIONS),) / (T, E) array.

    Returns:
        (T, V, 3) world vertex positions.
    """
    from wana.domain.skeleton import forward_kinematics

    rotations = np.asarray(rotations, float)
    pos, quat = forward_kinematics(
        rotations, np.asarray(root_position, float), character.offsets.astype(float)
    )
    rest = character.rest_joint_positions()
    base = character.vertices.astype(float)
    T = rotations.shape[0]
    if expression is not None:
        if isinstance(expression, dict):
            for k, wgt in expression.items():
                base = base + float(wgt) * character.blendshapes[k]
            base = np.broadcast_to(base, (T, *base.shape))
        else:
            e = np.broadcast_to(np.asarray(expression, float), (T, len(EXPRESSIONS)))
            stack = np.stack([character.blendshapes[k] for k in EXPRESSIONS])
            base = base[None] + np.einsum("te,evc->tvc", e, stack)
    else:
        base = np.broadcast_to(base, (T, *base.shape))
    from scipy.spatial.transform import Rotation  # 0.25 s of imports the pipeline's start does not need

    out = np.zeros((T, len(character.vertices), 3))
    for t in range(T):
        mats = Rotation.from_quat(quat[t]).as_matrix()  # (J, 3, 3)
        local = base[t][:, None, :] - rest[character.joints]  # (V, 4, 3)
        moved = np.einsum("vkij,vkj->vki", mats[character.joints], local) + pos[t][character.joints]
        out[t] = np.einsum("vk,vki->vi", character.weights, moved)
    return out
