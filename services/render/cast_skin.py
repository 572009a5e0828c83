"""A user's own character posed outside the GLB: its joints' world matrices over the motion, its mesh skinned
on them for the open3d renderer, and its skeleton as a BVH.

The pose is the one ``cast_gltf`` keys into the GLB (``cast_pose``: the story's motion retargeted onto the
rig's own joints and proportions), so the MP4, the USD and the BVH show the mesh and joints that the GLB and
the FBX carry.
"""

from __future__ import annotations

import io
import warnings
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from PIL import Image
from scipy.spatial.transform import Rotation

from proto.motion_data import Motion
from services.render.cast_gltf import CastCharacter, cast_pose
from wana.arrays import from_wire
from wana.cast.glb_rig import CastRig, Primitive, topological
from wana.domain import quat
from wana.domain.bvh import BvhClip

SRGB_GAMMA = 2.2  # glTF base colour factors are linear; the renderer's vertex colours are sRGB


def posed_local(cast: CastCharacter, motion: Motion, *, off_stage_scale: bool = True) -> np.ndarray:
    """(T, J, 4, 4) local matrices of the rig's joints on every frame, as the GLB animates them: rest
    translations and scales, the retargeted rotations, the Hips' translation; with ``off_stage_scale`` the
    Hips scaled to 0 where the character is off stage (USD hides it by visibility instead)."""
    rig = cast.rig
    pose = cast_pose(cast, motion)
    t = pose.rotation.shape[0]
    local = np.repeat(rig.local_matrices()[None], t, axis=0)
    q = pose.rotation / np.linalg.norm(pose.rotation, axis=-1, keepdims=True)
    local[:, :, :3, :3] = Rotation.from_quat(q.reshape(-1, 4)).as_matrix().reshape(t, -1, 3, 3)
    local[:, :, :3, :3] *= rig.scale[None, :, None, :]
    local[:, pose.hips, :3, 3] = pose.hips_translation
    if off_stage_scale and motion.present is not None:
        present = from_wire(motion.present).astype(bool)
        if len(present) == t:
            local[~present, pose.hips, :3, :3] = 0.0
    return local


def posed_world(cast: CastCharacter, motion: Motion) -> np.ndarray:
    """(T, J, 4, 4) world matrices of the rig's joints on every frame (the GLB's animation, evaluated)."""
    rig = cast.rig
    local = posed_local(cast, motion)
    world = np.zeros_like(local)
    for j in topological(rig.parents):
        p = int(rig.parents[j])
        world[:, j] = (rig.base[None] if p < 0 else world[:, p]) @ local[:, j]
    return world


def vertex_colours(prim: Primitive) -> np.ndarray:
    """(V, 3) sRGB 0..1: the base colour texture sampled at each vertex's UV, times the base colour."""
    factor = np.clip(np.asarray(prim.colour[:3], dtype=np.float64), 0.0, 1.0) ** (1.0 / SRGB_GAMMA)
    out = np.tile(factor, (len(prim.positions), 1))
    if prim.texture is not None and prim.uv is not None:
        try:
            img = np.asarray(Image.open(io.BytesIO(prim.texture[0])).convert("RGB"), dtype=np.float64) / 255.0
        except OSError:  # an image PIL cannot read: the base colour alone
            return out
        h, w = img.shape[:2]
        uv = np.mod(np.asarray(prim.uv, dtype=np.float64), 1.0)  # glTF's default sampler repeats
        x = np.clip((uv[:, 0] * w).astype(int), 0, w - 1)
        y = np.clip((uv[:, 1] * h).astype(int), 0, h - 1)  # glTF's v runs down the image
        out = out * img[y, x]
    return out


@dataclass
class CastBody:
    """The user's mesh skinned on its own joints, in the form the renderer draws a character.

    Attributes:
        rig: the user's character.
        world: (T, J, 4, 4) its joints' world matrices over the motion (``posed_world``).
        faces: (F, 3) all skinned primitives' triangles, into the concatenated vertices.
        colours: (V, 3) sRGB 0..1 per vertex.
    """

    rig: CastRig
    world: np.ndarray
    faces: np.ndarray
    colours: np.ndarray

    @classmethod
    def build(cls, cast: CastCharacter, motion: Motion) -> CastBody:
        faces, colours, start = [], [], 0
        for prim in cast.rig.primitives:
            faces.append(prim.indices.reshape(-1, 3).astype(np.int64) + start)
            colours.append(vertex_colours(prim))
            start += len(prim.positions)
        return cls(
            rig=cast.rig,
            world=posed_world(cast, motion),
            faces=np.concatenate(faces) if faces else np.zeros((0, 3), np.int64),
            colours=np.concatenate(colours) if colours else np.zeros((0, 3)),
        )

    @property
    def n_frames(self) -> int:
        return int(self.world.shape[0])

    @cached_property
    def rest_vertices(self) -> np.ndarray:
        """(V, 3) the mesh at the first frame (what the canvas is first given)."""
        return self.vertices([0])[0]

    def vertices(self, frames: np.ndarray | list[int]) -> np.ndarray:
        """(N, V, 3) world positions: glTF skinning (joint world @ inverse bind, blended by the weights)."""
        idx = np.clip(np.asarray(frames, dtype=np.int64), 0, self.n_frames - 1)
        out = []
        for prim in self.rig.primitives:
            skin = self.rig.skins[prim.skin]
            mats = np.einsum(
                "njab,jbc->njac", self.world[idx][:, skin.joints], skin.inverse_bind
            )  # (N, n, 4, 4)
            w = prim.weights.astype(np.float64)
            blend = np.einsum("vk,nvkab->nvab", w, mats[:, prim.joints.astype(np.int64)])  # (N, V, 4, 4)
            p = prim.positions.astype(np.float64)
            out.append(np.einsum("nvab,vb->nva", blend[..., :3, :3], p) + blend[..., :3, 3])
        return np.concatenate(out, axis=1) if out else np.zeros((len(idx), 0, 3))


def _depth_first(parents: np.ndarray) -> list[int]:
    order: list[int] = []
    stack = [j for j in range(len(parents)) if parents[j] < 0][::-1]
    while stack:
        j = stack.pop()
        order.append(j)
        stack.extend([k for k in range(len(parents)) if parents[k] == j][::-1])
    return order


def cast_clip(cast: CastCharacter, motion: Motion) -> BvhClip:
    """The rig's own skeleton as a BVH: its joint names and hierarchy, OFFSETs its rest bones in world metres,
    each joint's rotation the change of its world rotation from rest relative to its parent's (so a viewer's
    FK puts every joint where the GLB's does). Root: absolute position, ZYX rotations; others ZYX."""
    rig = cast.rig
    world = posed_world(cast, motion)
    rest = rig.rest_world()
    t, nj = world.shape[:2]
    roots = rig.parents < 0
    offsets = rest[:, :3, 3].copy()
    offsets[~roots] -= rest[rig.parents[~roots], :3, 3]
    offsets[roots] = 0.0  # the root's position channels are absolute

    def unit(m: np.ndarray) -> np.ndarray:  # rotation part without scale (scale 0 off stage: identity)
        r = m[..., :3, :3]
        n = np.linalg.norm(r, axis=-2, keepdims=True)
        return np.where(n > 1e-9, r / np.maximum(n, 1e-9), np.eye(3))

    delta = (
        Rotation.from_matrix(unit(world).reshape(-1, 3, 3))
        * Rotation.from_matrix(np.repeat(unit(rest)[None], t, axis=0).reshape(-1, 3, 3)).inv()
    )  # (T*J) world rotation change from rest
    g = delta.as_quat().reshape(t, nj, 4)
    local = g.copy()
    kids = ~roots
    parent_inv = Rotation.from_quat(g[:, rig.parents[kids]].reshape(-1, 4)).inv()
    local[:, kids] = (parent_inv * Rotation.from_quat(g[:, kids].reshape(-1, 4))).as_quat().reshape(t, -1, 4)
    with warnings.catch_warnings():  # Euler angles at gimbal lock are still exact rotations
        warnings.simplefilter("ignore", UserWarning)
        euler = quat.to_euler("ZYX", quat.normalize(local))  # (T, J, 3)
    order = _depth_first(rig.parents)  # the order BVH writes joints (and their channels) in
    cols, channels = [], []
    for j in order:
        if roots[j]:
            cols.append(world[:, j, :3, 3])
            channels.append(["Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation"])
        else:
            channels.append(["Zrotation", "Yrotation", "Xrotation"])
        cols.append(euler[:, j])
    new = {j: k for k, j in enumerate(order)}
    leaves = set(range(nj)) - set(int(p) for p in rig.parents if p >= 0)
    return BvhClip(
        joint_names=[rig.names[j] for j in order],
        parents=np.array([new[int(rig.parents[j])] if rig.parents[j] >= 0 else -1 for j in order]),
        offsets=offsets[order],
        channels=channels,
        end_sites={new[j]: np.array([0.0, 0.05, 0.0]) for j in leaves},
        frame_time=1.0 / float(motion.fps or 30),
        motion=np.concatenate(cols, axis=1),
    )
