"""Skinned characters: motion -> joint transforms -> linear-blend-skinned vertices (vectorised numpy).

A ``Rig`` pairs a character mesh (``wana.assets.characters.Character``) with one ``Motion``; its
joint transforms are computed once for all frames, so any frame range can be posed on its own
(render chunks need no state from earlier frames).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.spatial.transform import Rotation

from proto.motion_data import Motion
from services.render.camera import CharacterTrack
from wana.arrays import from_wire
from wana.assets.characters import EXPRESSIONS, Character, character_for
from wana.domain.skeleton import JOINT_INDEX, JOINT_NAMES, N_JOINTS, forward_kinematics


def motion_arrays(motion: Motion) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Root positions (T, 3), local rotations (T, J, 4) in canonical order, expression (T, E) or None.

    Raises:
        ValueError: shapes that do not fit the canonical skeleton.
    """
    root = from_wire(motion.root_position).astype(np.float64)
    rot = from_wire(motion.rotations).astype(np.float64)
    if rot.ndim != 3 or rot.shape[2] != 4:
        raise ValueError(f"motion {motion.character!r}: rotations must be (T, J, 4), got {rot.shape}")
    if motion.joint_names and list(motion.joint_names) != list(JOINT_NAMES):
        full = np.zeros((rot.shape[0], N_JOINTS, 4))
        full[..., 3] = 1.0
        for i, name in enumerate(motion.joint_names):
            if name in JOINT_INDEX and i < rot.shape[1]:
                full[:, JOINT_INDEX[name]] = rot[:, i]
        rot = full
    if rot.shape[1] != N_JOINTS:
        raise ValueError(
            f"motion {motion.character!r}: {rot.shape[1]} joints, the canonical skeleton has {N_JOINTS}"
        )
    if root.shape != (rot.shape[0], 3):
        raise ValueError(
            f"motion {motion.character!r}: root_position must be ({rot.shape[0]}, 3), got {root.shape}"
        )
    norms = np.linalg.norm(rot, axis=-1, keepdims=True)
    rot = np.where(norms > 1e-9, rot / np.maximum(norms, 1e-9), np.array([0.0, 0.0, 0.0, 1.0]))
    expr = None
    if motion.expression is not None:
        expr = from_wire(motion.expression).astype(np.float64)
        if expr.ndim != 2 or expr.shape[0] != rot.shape[0]:
            raise ValueError(
                f"motion {motion.character!r}: expression must be ({rot.shape[0]}, E), got {expr.shape}"
            )
    return root, rot, expr


@dataclass
class Rig:
    """A character and its motion, posed on demand.

    Attributes:
        character: the mesh and skin.
        root: (T, 3) Hips world positions.
        rotations: (T, J, 4) local quaternions.
        expression: (T, E) blendshape weights in ``EXPRESSIONS`` order, E <= len(EXPRESSIONS), or None.
        name: the character's name in the story.
    """

    character: Character
    root: np.ndarray
    rotations: np.ndarray
    expression: np.ndarray | None = None
    name: str = ""  # the story's name for the character ("" = the character's own)
    present: np.ndarray | None = None  # (T,) bool, on stage (None: always); off-stage frames skin to a point

    @classmethod
    def from_motion(cls, motion: Motion) -> Rig:
        root, rot, expr = motion_arrays(motion)
        return cls(
            character=character_for(motion.character),
            root=root,
            rotations=rot,
            expression=expr,
            name=motion.character,
            present=None if motion.present is None else from_wire(motion.present).astype(bool),
        )

    @property
    def n_frames(self) -> int:
        return int(self.root.shape[0])

    @cached_property
    def _fk(self) -> tuple[np.ndarray, np.ndarray]:
        return forward_kinematics(self.rotations, self.root, self.character.offsets.astype(np.float64))

    @property
    def joint_positions(self) -> np.ndarray:
        """(T, J, 3) world joint positions."""
        return self._fk[0]

    @property
    def joint_rotations(self) -> np.ndarray:
        """(T, J, 4) global joint quaternions."""
        return self._fk[1]

    @cached_property
    def _blendshape_stack(self) -> np.ndarray:
        shapes = self.character.blendshapes
        return np.stack([shapes.get(k, np.zeros_like(self.character.vertices)) for k in EXPRESSIONS]).astype(
            np.float64
        )

    def track(self) -> CharacterTrack:
        """Hips, facing (unit, XZ plane) and head over all frames, for cameras."""
        hips_rot = Rotation.from_quat(self.joint_rotations[:, 0])
        face = hips_rot.apply(np.array([0.0, 0.0, 1.0]))
        face[:, 1] = 0.0
        n = np.linalg.norm(face, axis=1, keepdims=True)
        face = np.where(n > 1e-6, face / np.maximum(n, 1e-6), np.array([0.0, 0.0, 1.0]))
        return CharacterTrack(
            hips=self.joint_positions[:, 0], facing=face, head=self.joint_positions[:, JOINT_INDEX["Head"]]
        )

    def vertices(self, frames: np.ndarray | list[int]) -> np.ndarray:
        """Linear-blend-skinned vertices with blendshapes applied.

        Args:
            frames: (N,) frame indices; indices past the end hold the last pose.

        Returns:
            (N, V, 3) world positions, metres.
        """
        idx = np.clip(np.asarray(frames, dtype=np.int64), 0, self.n_frames - 1)
        ch = self.character
        rest_joints = ch.rest_joint_positions()  # (J, 3)
        pos = self.joint_positions[idx]  # (N, J, 3)
        mats = (
            Rotation.from_quat(self.joint_rotations[idx].reshape(-1, 4))
            .as_matrix()
            .reshape(len(idx), N_JOINTS, 3, 3)
        )
        trans = pos - np.einsum("njab,jb->nja", mats, rest_joints)  # x' = R x + (p - R rest)
        base = np.broadcast_to(ch.vertices.astype(np.float64), (len(idx), *ch.vertices.shape))
        if self.expression is not None:
            e = self.expression[idx][:, : len(EXPRESSIONS)]
            base = base + np.einsum("ne,evc->nvc", e, self._blendshape_stack[: e.shape[1]])
        joints = ch.joints.astype(np.int64)  # (V, 4)
        w = ch.weights.astype(np.float64)  # (V, 4)
        blend_r = np.einsum("vk,nvkab->nvab", w, mats[:, joints])  # (N, V, 3, 3)
        blend_t = np.einsum("vk,nvka->nva", w, trans[:, joints])  # (N, V, 3)
        out = np.einsum("nvab,nvb->nva", blend_r, base) + blend_t
        if self.present is not None and len(self.present) == self.n_frames:
            gone = ~self.present[idx]
            out[gone] = pos[gone, :1]  # off stage: the whole mesh at the hips, scale 0 (nothing drawn)
        return out
