"""A lean ONNX rollout graph for the trained PFNN, written node by node (no torch tracing).

The traced `Rollout` graph spends most of its time on ~180 tiny nodes per step (the Catmull-Rom
coefficients, normalisation). This builder folds the input/output normalisation into the first
and last layers' weights and computes the phase coefficients exactly with a handful of nodes:
`coeff = [1, mu, mu^2, mu^3] @ Q[k]`, where k = floor(4 phase), mu = 4 phase - k and Q[k] (4, 4)
is the Catmull-Rom basis matrix with its columns rolled to the control sets that k selects. A step
is then ~25 nodes: three phase-blended layers (one MatMul over the four stacked control sets, a
(1, 4) x (4, n) MatMul for the blend), the autoregressive pose feedback and the phase update. The
graph unrolls `steps` frames per onnxruntime call and returns raw (denormalised) outputs, so it
is a drop-in replacement for the traced rollout (same inputs and outputs).

    python -m services.motion.pfnn_onnx            # models/locomotion/pfnn.pt -> pfnn_fast.onnx
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from services.motion.pfnn_layout import N_IN, N_OUT, N_POSE, N_SENSOR, N_TRAJ, SLICE_DPHASE, SLICE_POSE

FAST_STEPS = 60  # frames per onnxruntime call (2 s at 30 fps)
PHASE_BINS = 24  # precomputed phase locations: 24 keeps the table (7 MB float32) cache-friendly; mean pose deviation from the exact blend ~0.7 cm
N_CONTROL = N_TRAJ + N_SENSOR
# Catmull-Rom basis: w_i(mu) = [1, mu, mu^2, mu^3] @ BASIS[:, i], i = 0..3 for sets k-1, k, k+1, k+2.
BASIS = np.array(
    [[0.0, 1.0, 0.0, 0.0], [-0.5, 0.0, 0.5, 0.0], [1.0, -2.5, 2.0, -0.5], [-0.5, 1.5, -1.5, 0.5]]
)


def phase_basis() -> np.ndarray:
    """(4, 4, 4) Q[k]: powers of mu (4,) @ Q[k] -> weights of control sets 0..3 when floor(4 phase) = k."""
    q = np.zeros((4, 4, 4))
    for k in range(4):
        for i in range(4):
            q[k, :, (k + i - 1) % 4] += BASIS[:, i]
    return q


def folded_weights(state: dict[str, np.ndarray]) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per layer (W (n_in, 4 n_out), b (4 n_out,)) with the normalisation folded in.

    Args:
        state: the PFNN state dict as numpy arrays (l0/l1/l2 weight and bias, x/y mean and std).

    Returns:
        three (weight, bias) pairs; layer 0 takes raw X, layer 2 returns raw Y.
    """
    x_mean, x_std = state["x_mean"].astype(np.float64), state["x_std"].astype(np.float64)
    y_mean, y_std = state["y_mean"].astype(np.float64), state["y_std"].astype(np.float64)
    out = []
    for i in range(3):
        w = state[f"l{i}.weight"].astype(np.float64)
        b = state[f"l{i}.bias"].astype(np.float64)
        if i == 0:  # (x - m) / s @ W + b = x @ (W / s) + (b - (m / s) @ W)
            b = b - (x_mean / x_std) @ w
            w = w / x_std[:, None]
        if i == 2:  # Catmull-Rom weights sum to one, so the output mean can go into every set's bias
            n = w.shape[1] // 4
            w = w * np.tile(y_std, 4)[None]
            b = b * np.tile(y_std, 4) + np.tile(y_mean, 4)
            assert n == N_OUT
        out.append((w.astype(np.float32), b.astype(np.float32)))
    return out


def phase_tables(state: dict[str, np.ndarray], bins: int = PHASE_BINS) -> list[np.ndarray]:
    """Per layer the phase-blended weights, biases folded in, at the centres of `bins` phase bins.

    Bin i covers phases [i / bins, (i + 1) / bins) and holds the Catmull-Rom blend at (i + 0.5) / bins.
    Layer l's input ends with a constant 1 (its bias row); layers 0 and 1 emit an extra output that
    is always 1 (zero weights, bias 1; ELU keeps it 1) for the next layer, layer 2 an extra output
    equal to the phase change measured in bins (the graph's phase state).

    Returns:
        [(bins, 61 + N_POSE, hidden + 1), (bins, hidden + 1, hidden + 1), (bins, hidden + 1, N_OUT + 1)], float32;
        layer 0's rows are control (60), the constant 1, then the pose (N_POSE).
    """
    import torch

    from services.motion.pfnn import catmull_rom_coefficients

    phases = (torch.arange(bins, dtype=torch.float64).reshape(-1, 1) + 0.5) / bins
    coeff = catmull_rom_coefficients(phases).numpy()  # (bins, 4)
    out = []
    for i, (w, b) in enumerate(folded_weights(state)):
        n_in, n = w.shape[0], w.shape[1] // 4
        w_p = np.einsum("ps,isn->pin", coeff, w.astype(np.float64).reshape(n_in, 4, n))  # (bins, n_in, n)
        b_p = coeff @ b.astype(np.float64).reshape(4, n)  # (bins, n)
        full = np.concatenate([w_p, b_p[:, None]], axis=1)  # bias as the last input row
        if i == 0:  # rows: control, 1, pose
            full = np.concatenate([full[:, :N_CONTROL], full[:, -1:], full[:, N_CONTROL:-1]], axis=1)
        if i < 2:
            extra = np.zeros((bins, full.shape[1], 1))
            extra[:, N_CONTROL if i == 0 else -1, 0] = 1.0  # the constant-1 row -> 1
        else:
            extra = full[:, :, SLICE_DPHASE] * bins
        out.append(np.concatenate([full, extra], axis=2).astype(np.float32))
    return out


def build_rollout(state: dict[str, np.ndarray], steps: int = FAST_STEPS, bins: int = PHASE_BINS):
    """The rollout graph (onnx.ModelProto) for one character: control (1, steps, 60), pose (1, N_POSE),
    phase (1, 1) -> y (1, steps, N_OUT), last_pose (1, N_POSE), last_phase (1, 1).

    Per step: pick the phase bin, three (Gather weights, MatMul) layers with ELU, feed the pose back,
    advance the phase (kept in bin units inside the graph). Weights are stored as float16 (half the
    file) and cast to float32 once, when onnxruntime folds constants at session start.
    """
    import onnx
    from onnx import TensorProto, helper, numpy_helper

    inits = []
    nodes = []

    def const(name: str, value: np.ndarray) -> str:
        inits.append(numpy_helper.from_array(np.asarray(value), name))
        return name

    def node(op: str, inputs: list[str], output: str, **attrs) -> str:
        nodes.append(helper.make_node(op, inputs, [output], **attrs))
        return output

    for i, table in enumerate(phase_tables(state, bins)):
        node("Cast", [const(f"W{i}_half", table.astype(np.float16))], f"W{i}", to=TensorProto.FLOAT)
    const("bins", np.array(float(bins), np.float32))
    const("one", np.array(1.0, np.float32))
    const("scalar", np.zeros(0, np.int64))
    const("pads", np.array([0, 0, 0, 0, 0, 1], np.int64))
    const("shape_pose3", np.array([1, 1, N_POSE], np.int64))
    const("shape_pose", np.array([1, N_POSE], np.int64))
    const("shape_11", np.array([1, 1], np.int64))
    const("dphase_lo", np.array(0.0, np.float32))
    const("dphase_hi", np.array(0.5 * bins, np.float32))
    const("pose_start", np.array([SLICE_POSE.start], np.int64))
    const("pose_end", np.array([SLICE_POSE.stop], np.int64))
    const("dphase_start", np.array([N_OUT], np.int64))
    const("dphase_end", np.array([N_OUT + 1], np.int64))
    const("y_start", np.array([0], np.int64))
    const("y_end", np.array([N_OUT], np.int64))
    const("axis2", np.array([2], np.int64))
    split_sizes = const("split_sizes", np.ones(steps, np.int64))

    control = node(
        "Pad", ["control", "pads", "one"], "control_1", mode="constant"
    )  # (1, steps, 61): bias input
    ctrl_steps = [f"ctrl_{k}" for k in range(steps)]  # (1, 1, 61) each
    nodes.append(helper.make_node("Split", [control, split_sizes], ctrl_steps, axis=1))
    pose = node("Reshape", ["pose", "shape_pose3"], "pose_in")  # (1, 1, N_POSE)
    frac = node("Sub", ["phase", node("Floor", ["phase"], "phase_in_floor")], "phase_in_frac")
    phase = node(
        "Mul", [node("Mod", [frac, "one"], "phase_in", fmod=1), "bins"], "phase_bins"
    )  # in [0, bins)
    ys = []
    for k in range(steps):
        p = f"s{k}_"
        idx = node("Reshape", [node("Cast", [phase], p + "idx11", to=TensorProto.INT64), "scalar"], p + "idx")
        h = node("Concat", [ctrl_steps[k], pose], p + "x", axis=2)  # (1, 1, N_IN + 1)
        for i in range(3):
            w = node("Gather", [f"W{i}", idx], p + f"w{i}", axis=0)  # (n_in, n)
            z = node("MatMul", [h, w], p + f"z{i}")  # (1, 1, n)
            h = z if i == 2 else node("Elu", [z], p + f"h{i}", alpha=1.0)
        ys.append(h)
        pose = node("Slice", [h, "pose_start", "pose_end", "axis2"], p + "pose")
        dphase = node(
            "Clip",
            [
                node("Slice", [h, "dphase_start", "dphase_end", "axis2"], p + "dph_raw"),
                "dphase_lo",
                "dphase_hi",
            ],
            p + "dph",
        )
        phase = node(
            "Mod",
            [node("Add", [phase, node("Reshape", [dphase, "shape_11"], p + "dph11")], p + "ph_sum"), "bins"],
            p + "phase",
            fmod=1,
        )
    y_ext = node("Concat", ys, "y_ext", axis=1)  # (1, steps, N_OUT + 1)
    nodes.append(helper.make_node("Slice", [y_ext, "y_start", "y_end", "axis2"], ["y"]))
    nodes.append(helper.make_node("Reshape", [pose, "shape_pose"], ["last_pose"]))
    nodes.append(helper.make_node("Div", [phase, "bins"], ["last_phase"]))
    graph = helper.make_graph(
        nodes,
        "pfnn_rollout_fast",
        [
            helper.make_tensor_value_info("control", TensorProto.FLOAT, [1, steps, N_CONTROL]),
            helper.make_tensor_value_info("pose", TensorProto.FLOAT, [1, N_POSE]),
            helper.make_tensor_value_info("phase", TensorProto.FLOAT, [1, 1]),
        ],
        [
            helper.make_tensor_value_info("y", TensorProto.FLOAT, [1, steps, N_OUT]),
            helper.make_tensor_value_info("last_pose", TensorProto.FLOAT, [1, N_POSE]),
            helper.make_tensor_value_info("last_phase", TensorProto.FLOAT, [1, 1]),
        ],
        inits,
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)], producer_name="wana")
    model.ir_version = 8
    onnx.checker.check_model(model)
    return model


def state_from_checkpoint(path: Path) -> dict[str, np.ndarray]:
    """numpy state dict of models/locomotion/pfnn.pt."""
    import torch

    ck = torch.load(path, map_location="cpu", weights_only=True)
    return {k: v.numpy() for k, v in ck["state_dict"].items()}


def main(argv: list[str] | None = None) -> int:
    from services.motion.train_locomotion import MODEL_DIR

    parser = argparse.ArgumentParser(
        prog="python -m services.motion.pfnn_onnx",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--model-dir", type=Path, default=MODEL_DIR, help="folder with pfnn.pt (output goes there too)"
    )
    parser.add_argument("--steps", type=int, default=FAST_STEPS, help="frames unrolled per onnxruntime call")
    args = parser.parse_args(argv)
    import onnx

    model = build_rollout(state_from_checkpoint(args.model_dir / "pfnn.pt"), args.steps)
    onnx.save(model, args.model_dir / "pfnn_fast.onnx")
    print(
        f"wrote {args.model_dir / 'pfnn_fast.onnx'} ({args.steps} steps per call, {len(model.graph.node)} nodes)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())


assert N_IN == N_CONTROL + N_POSE
