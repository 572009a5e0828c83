"""The PFNN's input and output layout (sizes and slices), apart from the torch model (``pfnn.py``).

Inference (onnxruntime) and feature building need only the layout; keeping it here means they do not
import torch, which costs over a second of every start-up.
"""

from __future__ import annotations

from wana.domain.skeleton import N_JOINTS

TRAJ_OFFSETS = tuple(range(-30, 30, 5))  # frames at 30 fps: 12 samples
N_TRAJ = len(TRAJ_OFFSETS) * 4
N_SENSOR = 12
N_POSE = N_JOINTS * 6  # positions + velocities
N_IN = N_TRAJ + N_SENSOR + N_POSE
N_ROT = N_JOINTS * 4
N_OUT = N_POSE + N_ROT + 3 + 1 + 2
SLICE_POSE = slice(0, N_POSE)
SLICE_ROT = slice(N_POSE, N_POSE + N_ROT)
SLICE_ROOT = slice(N_POSE + N_ROT, N_POSE + N_ROT + 3)
SLICE_DPHASE = slice(N_POSE + N_ROT + 3, N_POSE + N_ROT + 4)
SLICE_CONTACT = slice(N_POSE + N_ROT + 4, N_OUT)
