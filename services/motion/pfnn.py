"""Phase-functioned neural network (Holden, Komura, Saito 2017) for locomotion, in torch.

Each layer's weights are a cyclic Catmull-Rom blend of four control sets chosen by the phase.
Input X (per frame): trajectory (12 samples, -1 s .. +0.83 s: local position x, z and direction x, z),
a local occupancy sensor (12), the previous pose (joint positions and velocities in the root
frame). Output Y: the pose (positions, velocities, local rotations with the hips relative to the
heading), root velocity (dx, dz, dyaw in the previous root frame), phase change, foot contacts.
Normalisation lives inside the module, so the exported ONNX graph takes and returns raw values.
`Rollout` unrolls K autoregressive steps in one graph so the controller pays one onnxruntime call
per K frames.
"""

from __future__ import annotations

import torch
from torch import nn

from services.motion.pfnn_layout import (  # re-exported: the layout is defined once, without torch
    N_IN,
    N_JOINTS,
    N_OUT,
    N_POSE,
    N_ROT,
    N_SENSOR,
    N_TRAJ,
    SLICE_CONTACT,
    SLICE_DPHASE,
    SLICE_POSE,
    SLICE_ROOT,
    SLICE_ROT,
    TRAJ_OFFSETS,
)

__all__ = [
    "N_IN",
    "N_JOINTS",
    "N_OUT",
    "N_POSE",
    "N_ROT",
    "N_SENSOR",
    "N_TRAJ",
    "SLICE_CONTACT",
    "SLICE_DPHASE",
    "SLICE_POSE",
    "SLICE_ROOT",
    "SLICE_ROT",
    "TRAJ_OFFSETS",
]


def catmull_rom_coefficients(phase: torch.Tensor) -> torch.Tensor:
    """Weights (B, 4) of the four control sets for phases (B, 1) in [0, 1)."""
    p = phase - torch.floor(phase)
    scaled = p * 4.0
    k1 = torch.floor(scaled)
    mu = scaled - k1
    mu2, mu3 = mu * mu, mu * mu * mu
    w = [
        -0.5 * mu + mu2 - 0.5 * mu3,
        1.0 - 2.5 * mu2 + 1.5 * mu3,
        0.5 * mu + 2.0 * mu2 - 1.5 * mu3,
        -0.5 * mu2 + 0.5 * mu3,
    ]
    sets = torch.arange(4, dtype=phase.dtype, device=phase.device).reshape(1, 4)
    coeff = torch.zeros(phase.shape[0], 4, dtype=phase.dtype, device=phase.device)
    for i in range(4):
        idx = k1 + (i - 1)
        idx = idx - 4.0 * (idx >= 4.0).to(idx.dtype) + 4.0 * (idx < 0.0).to(idx.dtype)
        coeff = coeff + w[i] * (sets == idx).to(phase.dtype)
    return coeff


class PhaseLinear(nn.Module):
    """A linear layer whose weights are a Catmull-Rom blend of 4 control sets."""

    def __init__(self, n_in: int, n_out: int) -> None:
        super().__init__()
        self.n_out = n_out
        self.weight = nn.Parameter(torch.randn(n_in, 4 * n_out) * (1.0 / n_in) ** 0.5)
        self.bias = nn.Parameter(torch.zeros(4 * n_out))

    def forward(self, x: torch.Tensor, coeff: torch.Tensor) -> torch.Tensor:
        y = (x @ self.weight + self.bias).reshape(x.shape[0], 4, self.n_out)
        return (y * coeff.unsqueeze(-1)).sum(dim=1)


class PFNN(nn.Module):
    """Raw X (B, N_IN), phase (B, 1) -> raw Y (B, N_OUT)."""

    def __init__(self, hidden: int = 256, dropout: float = 0.1) -> None:
        super().__init__()
        self.l0 = PhaseLinear(N_IN, hidden)
        self.l1 = PhaseLinear(hidden, hidden)
        self.l2 = PhaseLinear(hidden, N_OUT)
        self.drop = nn.Dropout(dropout)
        self.register_buffer("x_mean", torch.zeros(N_IN))
        self.register_buffer("x_std", torch.ones(N_IN))
        self.register_buffer("y_mean", torch.zeros(N_OUT))
        self.register_buffer("y_std", torch.ones(N_OUT))
        self.hidden = hidden

    def forward_normalized(self, xn: torch.Tensor, phase: torch.Tensor) -> torch.Tensor:
        c = catmull_rom_coefficients(phase)
        h = torch.nn.functional.elu(self.l0(self.drop(xn), c))
        h = torch.nn.functional.elu(self.l1(self.drop(h), c))
        return self.l2(self.drop(h), c)

    def forward(self, x: torch.Tensor, phase: torch.Tensor) -> torch.Tensor:
        x_mean, x_std, y_mean, y_std = (self.get_buffer(n) for n in ("x_mean", "x_std", "y_mean", "y_std"))
        yn = self.forward_normalized((x - x_mean) / x_std, phase)
        return yn * y_std + y_mean


class Rollout(nn.Module):
    """K autoregressive steps: control (B, K, N_TRAJ + N_SENSOR), pose (B, N_POSE), phase (B, 1).

    Returns Y (B, K, N_OUT), the last pose (B, N_POSE) and the last phase (B, 1).
    """

    def __init__(self, net: PFNN, steps: int) -> None:
        super().__init__()
        self.net = net
        self.steps = steps

    def forward(self, control: torch.Tensor, pose: torch.Tensor, phase: torch.Tensor):
        outs = []
        for k in range(self.steps):
            x = torch.cat([control[:, k], pose], dim=1)
            y = self.net(x, phase)
            outs.append(y)
            pose = y[:, SLICE_POSE]
            dphase = torch.clamp(y[:, SLICE_DPHASE], 0.0, 0.5)
            phase = phase + dphase
            phase = phase - torch.floor(phase)
        return torch.stack(outs, dim=1), pose, phase
