"""Score K candidate layouts of one interaction, each with its own re-synthesised motion, as a batch."""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from proto.motion_data import Motion
from proto.optimizer import ContactPair, CostReport, Interaction
from proto.scene import Scene
from services.optimizer.body import body_spheres, motion_joint_positions, shifted_from
from services.optimizer.collisions import BodyCollider
from services.optimizer.contacts import contact_bones, default_contacts, ik_chain
from services.optimizer.costs import (
    LayoutBatch,
    SceneGeometry,
    collision_cost,
    contact_distances,
    contact_points_world,
    joint_index,
    total_cost,
)
from wana.domain.actions import JOIN_FRAMES
from wana.domain.units import FPS

LOCOMOTION_ACTIONS = ("walk", "run", "jog", "turn", "locomotion")
APPROACH_S = 2.0  # the end of a walk into an action, during which touching the action's targets is contact


@dataclass(frozen=True)
class Scores:
    """Costs of K layouts.

    Attributes:
        cost: (K,) C = λ_D·C_D + λ_T·C_T.
        collision: (K,) C_D.
        contact: (K,) C_T, metres.
        distances: (K, P) per-pair contact distance, metres.
        box_hit: (K, B) box hit at any frame.
        locomotion_box_hit: (K, B) box hit during a walking segment.
    """

    cost: np.ndarray
    collision: np.ndarray
    contact: np.ndarray
    distances: np.ndarray
    box_hit: np.ndarray
    locomotion_box_hit: np.ndarray

    def report(self, k: int, pairs: list[ContactPair]) -> CostReport:
        """The CostReport of layout k."""
        return CostReport(
            cost=float(self.cost[k]),
            collision_cost=float(self.collision[k]),
            contact_cost=float(self.contact[k]),
            collided_boxes=int(self.box_hit[k].sum()),
            locomotion_collided_boxes=int(self.locomotion_box_hit[k].sum()),
            contact_distances=[float(d) for d in self.distances[k]],
            contact_pairs=list(pairs),
        )


def is_locomotion(action: str) -> bool:
    return action.split("_")[0] in LOCOMOTION_ACTIONS


def action_segment(motion: Motion, interaction: Interaction, n_frames: int) -> tuple[int, int]:
    """[start, end) frames of the interaction's action segment (the whole motion without segments)."""
    seg = _find_segment(motion, interaction)
    if seg is None:
        return 0, n_frames
    start, end = max(0, seg.start_frame), min(n_frames, seg.end_frame)
    return (start, end) if end > start else (0, n_frames)


def _find_segment(motion: Motion, interaction: Interaction):  # noqa: ANN202 - Segment | None
    segs = list(motion.segments)
    if not segs:
        return None
    if interaction.segment_index >= 0:
        if interaction.segment_index >= len(segs):
            raise ValueError(
                f"segment_index {interaction.segment_index} but the motion has {len(segs)} segments"
            )
        seg = segs[interaction.segment_index]
    else:
        named = [s for s in segs if s.action == interaction.action]
        others = [s for s in segs if not is_locomotion(s.action)]
        seg = (named or others or segs)[-1]
    return seg


def action_frames(motion: Motion, interaction: Interaction, n_frames: int) -> tuple[int, int]:
    """[start, end) frames over which the action's contacts hold (eq. 2 averages the joints over them).

    The interaction's segment, narrowed to the clip's contact window when the clip has one (a sit
    holds the seat only once seated); the whole motion without segments.
    """
    seg = _find_segment(motion, interaction)
    if seg is None:
        return 0, n_frames
    start, end = max(0, seg.start_frame), min(n_frames, seg.end_frame)
    window = contact_window(seg.action, motion.fps)
    if window is not None:  # the clip's contacts hold only part of it (sitting down, then seated)
        start, end = min(start + window[0], end - 1), min(start + window[1], end)
    elif end - start > 3 * JOIN_FRAMES:  # a loop holds between the blends from / into the rest pose
        start, end = start + JOIN_FRAMES, end - JOIN_FRAMES
    return (start, end) if end > start else (0, n_frames)


@functools.lru_cache(maxsize=256)
def contact_window(action: str, fps: int = FPS) -> tuple[int, int] | None:
    """[first, last) frame, from the clip's start, during which a non-looping clip holds its contacts.

    From the motion service's action library; None when the clip loops, has no window, or the
    library is not available.
    """
    try:
        from wana.domain.actions import get_clip

        clip = get_clip(action)
    except Exception:  # noqa: BLE001 - no library, or an action it does not know: the whole segment
        return None
    if clip.looping or clip.interaction is None:
        return None
    w0, w1 = clip.interaction.window
    first, last = int(round(w0 * fps)), int(round(w1 * fps))
    return (first, max(last, first + 1))


class InteractionScorer:
    """Everything about one interaction that does not change between proposals, precomputed."""

    def __init__(
        self,
        scene: Scene,
        interaction: Interaction,
        *,
        lambda_d: float = 1.0,
        lambda_t: float = 10.0,
        contact_tolerance: float = 0.06,
        frame_stride: int = 2,
        action_frames_max: int | None = None,
        geometry: SceneGeometry | None = None,
        coarse: bool = False,
        ik_reach: bool = False,
    ) -> None:
        """Args:
        scene: the layout whose objects (ids, variants) all candidates share.
        interaction: the action, its targets and contacts.
        lambda_d: weight of C_D.
        lambda_t: weight of C_T per metre.
        contact_tolerance: penetration (metres) into a target object tolerated while the action holds.
        frame_stride: collisions are tested on every stride-th frame (30 fps / 2 = 15 Hz by default).
        action_frames_max: at most this many tested frames per non-walking segment; None = no cap.
        geometry: the scene's object geometry; read from the asset catalog when None.
        coarse: cell-level collision test (fast, to rank proposals); walking hits are then not
            told apart (``locomotion_box_hit`` stays empty).
        ik_reach: score hand contacts as the motion service's arm IK would meet them: a contact
            point within arm's reach of the mean shoulder costs nothing, beyond it the overshoot.
            For ranking proposals with a motion that is not re-solved per proposal (the anchored
            surrogate); reports leave it off and measure the motion's joints (eq. 2).
        """
        self.coarse = coarse
        self.interaction = interaction
        self.geom = geometry if geometry is not None else SceneGeometry.from_scene(scene)
        if self.geom.ids != tuple(o.id for o in scene.objects):
            raise ValueError("geometry object ids do not match the scene's objects")
        self.lambda_d, self.lambda_t = lambda_d, lambda_t
        self.contact_tolerance = contact_tolerance
        self.frame_stride = max(1, int(frame_stride))
        self.action_frames_max = action_frames_max
        self.collider = BodyCollider(self.geom)
        self.spheres = body_spheres(spacing=2.0 if coarse else 1.0)
        ids = self.geom.ids
        for t in interaction.targets:
            if t not in ids:
                raise ValueError(
                    f"interaction target {t!r} is not an object of the scene; objects are {list(ids)}"
                )
        pairs = list(interaction.contacts) or default_contacts(self.geom, interaction)
        for p in pairs:
            if p.object_id not in ids:
                raise ValueError(f"contact object {p.object_id!r} is not an object of the scene")
        self.contact_idx = np.array(
            [self.geom.contact_index(p.object_id, p.point, p.joint) for p in pairs], dtype=np.int64
        )
        # Name the joint of every pair (a pair given without one takes the contact point's).
        self.pairs = [
            ContactPair(object_id=p.object_id, point=p.point, joint=self.geom.contact_joints[c])
            for p, c in zip(pairs, self.contact_idx, strict=True)
        ]
        pairs = self.pairs
        self.joint_idx = joint_index([p.joint for p in pairs])
        chains = [ik_chain(p.joint) if ik_reach else None for p in pairs]
        self.ik_mask = np.array([c is not None for c in chains], dtype=bool)
        self.ik_root = np.array([c[0] if c else 0 for c in chains], dtype=np.int64)
        self.ik_len = np.array([c[1] * 0.95 if c else 0.0 for c in chains])
        self._tracks: dict[int, tuple[np.ndarray, tuple[np.ndarray, ...]]] = {}
        self._radius_tile = np.zeros(0)
        self._frames: dict[int, np.ndarray] = {}
        self._bones_tile = np.zeros((0, len(ids)), dtype=bool)
        supports = {o.id: o.support for o in scene.objects if o.support}
        self.contact_bones = contact_bones(self.spheres, self.pairs, ids, supports)  # (S, O)
        self.is_target = np.array([i in interaction.targets for i in ids], dtype=bool)

    def score(self, layout: LayoutBatch, motions: list[Motion]) -> Scores:
        """Costs of K layouts, the k-th with motions[k]."""
        k_ = len(motions)
        if layout.position.shape[0] != k_:
            raise ValueError(f"{layout.position.shape[0]} layouts but {k_} motions")
        positions = [motion_joint_positions(m) for m in motions]
        tracks = [self._track(m, p) for m, p in zip(motions, positions, strict=True)]
        s_ = len(self.spheres.radius)
        n_max = max(len(tr[0]) for tr in tracks)
        if len(self._radius_tile) < n_max:
            self._radius_tile = np.tile(self.spheres.radius, n_max // s_)
        centres = np.zeros((k_, n_max, 3))
        radius = np.zeros((k_, n_max))
        act = np.zeros((k_, n_max), dtype=bool)
        appr = np.zeros((k_, n_max), dtype=bool)
        loco = np.zeros((k_, n_max), dtype=bool)
        joint_mean = np.zeros((k_, len(self.pairs), 3))
        root_mean = np.zeros((k_, len(self.pairs), 3))
        f_max = n_max // s_
        pose_lo = np.full((k_, f_max, 3), np.inf)
        pose_hi = np.full((k_, f_max, 3), -np.inf)
        for k, (m, p, (c, a, ap, lc, plo, phi)) in enumerate(zip(motions, positions, tracks, strict=True)):
            pose_lo[k, : len(plo)], pose_hi[k, : len(plo)] = plo, phi
            n = len(c)
            centres[k, :n] = c
            radius[k, :n] = self._radius_tile[:n]
            act[k, :n] = a
            appr[k, :n] = ap
            loco[k, :n] = lc
            if len(self.pairs):
                a0, a1 = action_frames(m, self.interaction, len(p))
                joint_mean[k] = p[a0:a1][:, self.joint_idx].mean(axis=0)
                if self.ik_mask.any():
                    root_mean[k] = p[a0:a1][:, self.ik_root].mean(axis=0)
        # Touching a target while the action holds is contact: a small tolerance for the body, and the
        # contact joints' own bones may rest on their object; in the last APPROACH_S of the walk that
        # brings the character to its targets, they do not count at all (one walks right up to a chair).
        if len(self._bones_tile) != n_max:
            self._bones_tile = np.tile(self.contact_bones, (n_max // s_, 1))  # (N, O)
        target = self.is_target[None, None, :]
        reach = radius[..., None] - self.contact_tolerance * (act[..., None] & target)
        reach[(self._bones_tile[None] & act[..., None]) | (appr[..., None] & target)] = 0.0
        box_hit = np.zeros((k_, len(self.geom.box_owner)), dtype=bool)
        loco_hit = np.zeros_like(box_hit)
        for ks, b in self.collider.hits(
            centres, reach, layout, coarse=self.coarse, group=s_, pose_bounds=(pose_lo, pose_hi)
        ):
            box_hit[ks[:, 0], b] = True
            if not self.coarse:
                lh = loco[ks[:, 0], ks[:, 1]]
                loco_hit[ks[lh, 0], b[lh]] = True
        c_d = collision_cost(box_hit, self.geom)
        if len(self.pairs):
            points = contact_points_world(self.geom, layout, self.contact_idx)
            dist = contact_distances(points, joint_mean)
            if self.ik_mask.any():
                over = np.maximum(np.linalg.norm(points - root_mean, axis=-1) - self.ik_len[None], 0.0)
                dist = np.where(self.ik_mask[None], over, dist)
            c_t = dist.mean(axis=1)
        else:
            dist, c_t = np.zeros((k_, 0)), np.zeros(k_)
        return Scores(total_cost(c_d, c_t, self.lambda_d, self.lambda_t), c_d, c_t, dist, box_hit, loco_hit)

    def frames(self, motion: Motion, n_frames: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Frames whose body is tested for collisions, and which are in an action / approaching one / walking.

        Walking frames are taken every ``frame_stride``; frames of other segments every stride too,
        but at most ``action_frames_max`` per segment, evenly spread (their poses change slowly).

        Returns:
            frame indices (F,), in-action flags (F,) (any non-walking segment: the targets are touched
            on purpose), approach flags (F,) (the last APPROACH_S seconds of a walk that ends in an action), walking
            flags (F,).
        """
        segs = sorted(motion.segments, key=lambda s: s.start_frame) or []
        approach = np.zeros(n_frames, dtype=bool)
        acting = np.zeros(n_frames, dtype=bool) if segs else np.ones(n_frames, dtype=bool)
        for i, seg in enumerate(segs):
            if not is_locomotion(seg.action):
                acting[max(0, seg.start_frame) : seg.end_frame] = True
            elif i + 1 < len(segs) and not is_locomotion(segs[i + 1].action):
                approach[
                    max(seg.start_frame, seg.end_frame - int(APPROACH_S * motion.fps)) : seg.end_frame
                ] = True
        pieces: list[np.ndarray] = []
        walking: list[np.ndarray] = []
        covered = 0
        for seg in segs:
            lo, hi = max(seg.start_frame, covered), min(seg.end_frame, n_frames)
            if hi <= lo:
                continue
            f = np.arange(lo, hi, self.frame_stride)
            walk = is_locomotion(seg.action)
            if not walk and self.action_frames_max and len(f) > self.action_frames_max:
                f = np.unique(np.linspace(lo, hi - 1, self.action_frames_max).round().astype(np.int64))
            pieces.append(f)
            walking.append(np.full(len(f), walk))
            covered = hi
        if covered < n_frames:
            f = np.arange(covered, n_frames, self.frame_stride)
            if self.action_frames_max and len(f) > self.action_frames_max:
                f = np.unique(
                    np.linspace(covered, n_frames - 1, self.action_frames_max).round().astype(np.int64)
                )
            pieces.append(f)
            walking.append(np.zeros(len(f), dtype=bool))
        frames = np.concatenate(pieces) if pieces else np.zeros(0, np.int64)
        loco = np.concatenate(walking) if walking else np.zeros(0, bool)
        return frames, acting[frames], approach[frames], loco

    def _track(self, motion: Motion, positions: np.ndarray) -> tuple[np.ndarray, ...]:
        """Sphere centres (F * S, 3), per-sphere flags of ``frames`` and per-pose bounds (F, 3) x2, memoised."""
        hit = self._tracks.get(id(positions))
        if hit is not None and hit[0] is positions:
            return hit[1]
        derived = shifted_from(positions)
        if (
            derived is not None
            and id(derived[0]) in self._tracks
            and self._tracks[id(derived[0])][0] is derived[0]
        ):
            # A translated copy of a motion already tracked (the anchored surrogate): shift its spheres.
            base = self._tracks[id(derived[0])][1]
            frames = self._frames[id(derived[0])]
            d = derived[1][frames]  # (F, 3)
            s_ = len(self.spheres.radius)
            track = (
                (base[0].reshape(len(frames), s_, 3) + d[:, None, :]).reshape(-1, 3),
                *base[1:4],
                base[4] + d,
                base[5] + d,
            )
            self._remember(positions, track)
            return track
        frames, act, appr, loco = self.frames(motion, len(positions))
        self._frames[id(positions)] = frames
        centres = self.spheres.centres(positions[frames])  # (F, S, 3)
        rmax = self.spheres.radius.max()
        s_ = centres.shape[1]
        track = (
            centres.reshape(-1, 3),
            np.repeat(act, s_),
            np.repeat(appr, s_),
            np.repeat(loco, s_),
            centres.min(axis=1) - rmax,
            centres.max(axis=1) + rmax,
        )
        self._remember(positions, track)
        return track

    def _remember(self, positions: np.ndarray, track: tuple[np.ndarray, ...]) -> None:
        if len(self._tracks) >= 64:
            # Keep the first (the input motion, base of the translated ones); drop the oldest other.
            self._tracks.pop(list(self._tracks)[1])
        self._tracks[id(positions)] = (positions, track)  # holding positions keeps the id unique

    def score_scenes(self, scenes: list[Scene], motions: list[Motion]) -> Scores:
        """Costs of K scenes (same objects as the scorer's scene) with their motions."""
        return self.score(LayoutBatch.from_scenes(scenes), motions)
