"""Train the locomotion PFNN and export it to ONNX (normalisation inside the graph).

Usage (CPU, one thread: 90 s wall for the shipped model on a busy 2-core machine, 75 s of it training):
    OMP_NUM_THREADS=1 nice -n 10 .venv/bin/python -m services.motion.train_locomotion

Corpus: (a) procedural locomotion from services.motion.gait (walk, run, start, stop, turn,
side-step at varied speeds, with random obstacles for the occupancy sensor), (b) the CMU
locomotion clips of ../shared/data/cmu_mocap_iclone and (c) the CMU walk/run takes of
../shared/data/cmu_locomotion_daz (Daz skeleton; subjects 8, 9, 10 and the takes the iClone set lacks),
both retargeted to the canonical skeleton when those folders exist (training works without them).
Subjects 2, 5 and 12 of (c) are held out for eval/gait.py (HELD_OUT_SUBJECTS). Writes
models/locomotion/{pfnn.pt, pfnn_step.onnx, pfnn_rollout.onnx, pfnn_fast.onnx, meta.json}.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import time
from itertools import chain
from pathlib import Path

import numpy as np

from services.motion.gait import random_trajectory, synthesize_gait
from services.motion.locomotion_features import build_xy
from wana.domain import quat
from wana.domain.paths import model_path, repo_root
from wana.domain.units import FPS

REPO = repo_root() or Path.cwd()  # training runs from a checkout (reads ../shared/data beside it)
MODEL_DIR = model_path("locomotion")
SHARED = Path(os.environ.get("WANA_SHARED_DATA", REPO.parent / "shared" / "data"))
ROLLOUT_STEPS = 10
SEED = 1234


def _obstacles(rng: np.random.Generator, pos: np.ndarray):
    centres = pos[rng.integers(0, len(pos), 6)] + rng.normal(0, 1.2, (6, 2))
    radii = rng.uniform(0.2, 0.6, 6)
    # keep obstacles off the path itself
    keep = np.array(
        [np.min(np.linalg.norm(pos - c, axis=1)) > r + 0.3 for c, r in zip(centres, radii, strict=True)]
    )
    centres, radii = centres[keep], radii[keep]

    def occupied(pts: np.ndarray) -> np.ndarray:
        if not len(centres):
            return np.zeros(len(pts), bool)
        return np.any(np.linalg.norm(pts[:, None] - centres[None], axis=-1) < radii[None], axis=1)

    return occupied


def procedural_corpus(n_sequences: int, seconds: float, seed: int = SEED):
    rng = np.random.default_rng(seed)
    for _ in range(n_sequences):
        pos, heading, speed = random_trajectory(rng, seconds)
        g = synthesize_gait(pos, heading, speed, phase0=rng.uniform())
        yield g["root_position"], g["rotations"], heading, g["phase"], g["contacts"], _obstacles(rng, pos)


def label_phase(contacts: np.ndarray) -> np.ndarray:
    """Phase (T,) from foot contacts: 0 at each left touch-down, 0.5 at each right touch-down."""
    t = len(contacts)
    events = []
    for k, val in ((0, 0.0), (1, 0.5)):
        on = np.where((contacts[1:, k] == 1) & (contacts[:-1, k] == 0))[0] + 1
        events += [(i, val) for i in on]
    events.sort()
    if len(events) < 2:
        return np.mod(np.arange(t) / FPS, 1.0)
    idx = np.array([e[0] for e in events], float)
    vals = np.array([e[1] for e in events])
    unwrapped = [vals[0]]
    for v in vals[1:]:
        nxt = unwrapped[-1] + np.mod(v - unwrapped[-1], 1.0)
        unwrapped.append(nxt if nxt > unwrapped[-1] else nxt + 1.0)
    ph = np.interp(np.arange(t), idx, unwrapped)
    period = np.median(np.diff(idx)) * 2
    ph[: int(idx[0])] = unwrapped[0] - (idx[0] - np.arange(int(idx[0]))) / period
    last = int(idx[-1])
    ph[last:] = unwrapped[-1] + (np.arange(last, t) - idx[-1]) / period
    return np.mod(ph, 1.0)


def annotate(root: np.ndarray, rot: np.ndarray, lock: bool = False):
    """Heading (smoothed hips yaw), phase and foot contacts of a retargeted clip: the training tuple.

    lock: pin the planted feet (services.motion.ik.lock_feet). Our legs' proportions are not the
    subject's, so a retargeted planted foot slides about 0.9 cm per frame; locked, 0.06.
    """
    from services.motion.retarget import ANKLE_HEIGHT
    from wana.domain.skeleton import JOINT_INDEX, forward_kinematics

    fwd = quat.rotate(rot[:, 0], np.broadcast_to([0.0, 0.0, 1.0], (len(rot), 3)))
    heading = np.unwrap(np.arctan2(fwd[:, 0], fwd[:, 2]))
    heading = np.convolve(np.pad(heading, 7, mode="edge"), np.ones(15) / 15, mode="valid")
    pos, _ = forward_kinematics(rot, root)
    speed = (
        float(np.linalg.norm(np.diff(root[:, [0, 2]], axis=0), axis=1).mean() * FPS) if len(root) > 1 else 0.0
    )
    contacts = np.zeros((len(rot), 2), np.uint8)
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        f = pos[:, JOINT_INDEX[name]]
        v = np.zeros(len(f))
        v[1:] = np.linalg.norm(np.diff(f, axis=0), axis=1) * FPS
        # The retarget puts a planted ankle at 6 cm (services.motion.retarget.ANKLE_HEIGHT); the foot rolls
        # from heel to toe, lifting the ankle a few cm while it stays planted. A running stance lasts a few
        # frames, over which a rolling ankle moves faster than 0.6 m/s.
        contacts[:, k] = clean_contacts(
            (f[:, 1] < ANKLE_HEIGHT + 0.05) & (v < max(0.6, 0.3 * speed)), 2 if speed > 2.2 else 3
        )
    if lock:
        from services.motion.ik import lock_feet

        rot = lock_feet(rot, root, contacts)
    return root, rot, heading, label_phase(contacts), contacts, None


def clean_contacts(flags: np.ndarray, shortest: int = 3) -> np.ndarray:
    """(T,) uint8 contacts without flicker: gaps and then runs shorter than `shortest` frames are removed
    (a flickering flag gives a touch-down per flicker, and the phase labels would spin)."""
    c = flags.astype(np.uint8).copy()
    for value in (0, 1):  # fill short gaps, then drop short runs
        edges = np.flatnonzero(np.diff(np.concatenate([[1 - value], c, [1 - value]])))
        for s, e in zip(edges[::2], edges[1::2], strict=True):
            if e - s < shortest and s > 0 and e < len(c):
                c[s:e] = 1 - value
    return c


def cmu_corpus(shared: Path = SHARED):
    """Retargeted CMU locomotion clips (skeleton variant A) with heading, phase and contacts."""
    from services.motion.retarget import retarget_clip
    from wana.domain.bvh import read_bvh

    labels = shared / "cmu_mocap_iclone" / "labels.csv"
    if not labels.is_file():
        return
    with labels.open() as fh:
        rows = [
            r
            for r in csv.DictReader(fh)
            if r["category"] == "locomotion" and r["skeleton_variant"].startswith("A")
        ]
    for r in held_in(rows):
        yield annotate(*retarget_clip(read_bvh(shared / "cmu_mocap_iclone" / r["file"])), lock=True)


# Subjects of ../shared/data/cmu_locomotion_daz kept out of training for eval/gait.py: 2 (walk, run), 5 (walk)
# and 12 (three walks), 26 s of 121 s. Subject 5 is also out of the iClone set (its only trial, 005_01).
HELD_OUT_SUBJECTS = (2, 5, 12)


def daz_rows(shared: Path = SHARED) -> list[dict]:
    """labels.csv rows of the Daz-skeleton CMU locomotion trials (empty when the folder is absent)."""
    labels = shared / "cmu_locomotion_daz" / "labels.csv"
    if not labels.is_file():
        return []
    with labels.open() as fh:
        return list(csv.DictReader(fh))


def daz_clip(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """One Daz-skeleton trial retargeted to ours at 30 fps: root (T, 3), rotations (T, J, 4).

    Frame 0 of every file in that conversion is its rest T-pose (root at the first captured frame) and the
    next four blend from it into the capture (the arms sweep down in 1/30 s), so the first 1/20 s is
    dropped, and so are further leading frames before a root jump (09_10 starts with stray frames).
    """
    from services.motion.retarget import DAZ_MAP, retarget_clip
    from wana.domain.bvh import read_bvh

    clip = read_bvh(path)
    motion = clip.motion[1 + int(round(0.05 * clip.fps)) :]
    step = np.linalg.norm(np.diff(motion[:, :3], axis=0), axis=1)  # hip position channels come first
    jumps = np.where(step[:10] > 5 * np.median(step) + 1e-6)[0]
    clip.motion = motion[int(jumps[-1]) + 1 if len(jumps) else 0 :]
    return retarget_clip(clip, DAZ_MAP)


def daz_training_rows(shared: Path = SHARED) -> list[dict]:
    """Daz-skeleton trials for training: not a held-out subject and not a capture the iClone set already has
    (subjects 3, 6 and 7 are in both conversions: the same takes)."""
    iclone = shared / "cmu_mocap_iclone" / "labels.csv"
    seen: set[tuple[int, int]] = set()
    if iclone.is_file():
        with iclone.open() as fh:
            seen = {(int(r["subject"]), int(r["trial"])) for r in csv.DictReader(fh)}
    return [
        r
        for r in daz_rows(shared)
        if int(r["subject"]) not in HELD_OUT_SUBJECTS
        and (int(r["subject"]), int(r["trial"])) not in seen
        and "stride" not in r["description"]  # 08_05, 08_07, 08_11: acted long strides, not a plain walk
    ]


def daz_heldout_rows(shared: Path = SHARED) -> list[dict]:
    """Daz-skeleton trials of the held-out subjects (eval/gait.py)."""
    return [r for r in daz_rows(shared) if int(r["subject"]) in HELD_OUT_SUBJECTS]


def daz_corpus(shared: Path = SHARED):
    """Training tuples of the Daz-skeleton trials of the training subjects (glitching takes left out)."""
    for r in daz_training_rows(shared):
        root, rot = daz_clip(shared / "cmu_locomotion_daz" / r["file"])
        if plausible(root):
            yield annotate(root, rot, lock=True)


def plausible(root: np.ndarray, max_speed: float = 8.0) -> bool:
    """False for a take whose root jumps faster than anyone runs (09_10 has a two-frame 9 m/s glitch)."""
    return bool(len(root) < 2 or np.max(np.linalg.norm(np.diff(root, axis=0), axis=1)) * FPS <= max_speed)


def held_in(rows: list[dict]) -> list[dict]:
    """Training clips: every CMU locomotion clip except the held-out ones (eval/motion.py uses those)."""
    return [r for r in rows if r["file"] not in HELD_OUT]


HELD_OUT = ("bvh/007_12.bvh.gz", "bvh/005_01.bvh.gz")


def build_dataset(n_sequences: int, seconds: float, use_cmu: bool = True, cmu_weight: int = 3):
    xs, ps, ys = [], [], []
    n_cmu = 0
    for seq in procedural_corpus(n_sequences, seconds):
        x, p, y = build_xy(*seq)
        xs.append(x)
        ps.append(p)
        ys.append(y)
    if use_cmu:
        for seq in chain(cmu_corpus(), daz_corpus()):
            root, rot, heading, phase, contacts, occupied = seq
            x, p, y = build_xy(root, rot, heading, phase, contacts, occupied, extrapolate=True)
            for _ in range(cmu_weight):  # upweight the captured clips
                xs.append(x)
                ps.append(p)
                ys.append(y)
            n_cmu += len(x)
    return np.concatenate(xs), np.concatenate(ps), np.concatenate(ys), n_cmu


def train(args: argparse.Namespace) -> dict:
    import torch

    from services.motion.pfnn import PFNN, SLICE_ROT

    torch.manual_seed(SEED)
    torch.set_num_threads(args.threads)
    t0 = time.time()
    x, p, y, n_cmu = build_dataset(args.sequences, args.seconds, not args.no_cmu, args.cmu_weight)
    print(f"corpus: {len(x)} frames ({n_cmu} from CMU) built in {time.time() - t0:.1f}s")
    net = PFNN(hidden=args.hidden)
    x_mean, x_std = x.mean(0), x.std(0) + 1e-3
    y_mean, y_std = y.mean(0), y.std(0) + 1e-3
    for name, val in (("x_mean", x_mean), ("x_std", x_std), ("y_mean", y_mean), ("y_std", y_std)):
        getattr(net, name).copy_(torch.from_numpy(val))
    xn = torch.from_numpy((x - x_mean) / x_std)
    yn = torch.from_numpy((y - y_mean) / y_std)
    pt = torch.from_numpy(p)
    opt = torch.optim.AdamW(net.parameters(), lr=args.lr, weight_decay=1e-4)
    n = len(xn)
    steps_per_epoch = n // args.batch
    total = steps_per_epoch * args.epochs
    sched = torch.optim.lr_scheduler.OneCycleLR(opt, max_lr=args.lr, total_steps=total)
    gen = torch.Generator().manual_seed(SEED)
    from services.motion.pfnn_layout import N_SENSOR, N_TRAJ

    noise = torch.full((1, xn.shape[1]), 0.05)
    noise[:, N_TRAJ + N_SENSOR :] = args.pose_noise
    from tqdm import tqdm

    bar = tqdm(total=total, desc="train pfnn", mininterval=5)
    loss_v = float("nan")
    for _epoch in range(args.epochs):
        perm = torch.randperm(n, generator=gen)
        for b in range(steps_per_epoch):
            idx = perm[b * args.batch : (b + 1) * args.batch]
            xb = xn[idx]
            # robustness to its own autoregressive drift: noise on every input, more on the previous pose
            # (so that the trajectory, not the pose alone, decides how fast the next step goes)
            xb = xb + noise * torch.randn(xb.shape, generator=gen)
            pred = net.forward_normalized(xb, pt[idx])
            loss = torch.mean((pred - yn[idx]) ** 2)
            opt.zero_grad()
            loss.backward()
            opt.step()
            sched.step()
            loss_v = float(loss)
            bar.update(1)
            bar.set_postfix(loss=f"{loss_v:.4f}")
            if time.time() - t0 > args.max_minutes * 60:
                break
        if time.time() - t0 > args.max_minutes * 60:
            print("time budget reached, stopping early")
            break
    bar.close()
    net.eval()
    with torch.no_grad():
        val = torch.mean((net.forward_normalized(xn[:4096], pt[:4096]) - yn[:4096]) ** 2).item()
        rot_err = torch.mean(
            (
                net(torch.from_numpy(x[:4096]), pt[:4096])[:, SLICE_ROT]
                - torch.from_numpy(y[:4096, SLICE_ROT])
            ).abs()
        ).item()
    return {
        "net": net,
        "loss": loss_v,
        "fit_mse": val,
        "rot_mae": rot_err,
        "frames": int(len(x)),
        "cmu_frames": int(n_cmu),
        "seconds": time.time() - t0,
    }


def export(net, out: Path) -> None:
    """Write pfnn.pt, pfnn_step.onnx and pfnn_rollout.onnx (ROLLOUT_STEPS steps per call)."""
    import torch

    from services.motion.pfnn import N_IN, N_POSE, N_SENSOR, N_TRAJ, Rollout

    out.mkdir(parents=True, exist_ok=True)
    torch.save({"hidden": net.hidden, "state_dict": net.state_dict()}, out / "pfnn.pt")
    net.eval()
    x = torch.zeros(1, N_IN)
    ph = torch.zeros(1, 1)
    torch.onnx.export(
        net,
        (x, ph),
        out / "pfnn_step.onnx",
        input_names=["x", "phase"],
        output_names=["y"],
        dynamic_axes={"x": {0: "batch"}, "phase": {0: "batch"}, "y": {0: "batch"}},
        opset_version=17,
        dynamo=False,
    )
    roll = Rollout(net, ROLLOUT_STEPS)
    ctrl = torch.zeros(1, ROLLOUT_STEPS, N_TRAJ + N_SENSOR)
    pose = torch.zeros(1, N_POSE)
    torch.onnx.export(
        roll,
        (ctrl, pose, ph),
        out / "pfnn_rollout.onnx",
        input_names=["control", "pose", "phase"],
        output_names=["y", "last_pose", "last_phase"],
        dynamic_axes={"control": {0: "batch"}, "pose": {0: "batch"}, "phase": {0: "batch"}},
        opset_version=17,
        dynamo=False,
    )


def load_torch(model_dir: Path = MODEL_DIR):
    """The trained torch PFNN (eval mode)."""
    import torch

    from services.motion.pfnn import PFNN

    ck = torch.load(model_dir / "pfnn.pt", map_location="cpu", weights_only=True)
    net = PFNN(hidden=ck["hidden"])
    net.load_state_dict(ck["state_dict"])
    return net.eval()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m services.motion.train_locomotion",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--sequences", type=int, default=80, help="procedural sequences (default 80)")
    parser.add_argument("--seconds", type=float, default=20.0, help="seconds per procedural sequence")
    parser.add_argument("--hidden", type=int, default=64, help="hidden units per layer (default 64)")
    parser.add_argument("--epochs", type=int, default=15)
    parser.add_argument("--batch", type=int, default=256)
    parser.add_argument("--lr", type=float, default=2e-3)
    parser.add_argument("--threads", type=int, default=1, help="torch CPU threads")
    parser.add_argument("--max-minutes", type=float, default=12.0, help="stop training after this wall time")
    parser.add_argument("--no-cmu", action="store_true", help="procedural corpus only")
    parser.add_argument("--cmu-weight", type=int, default=3, help="times each captured clip is repeated")
    parser.add_argument(
        "--pose-noise", type=float, default=0.5, help="noise on the previous pose (normalised)"
    )
    parser.add_argument("--out", type=Path, default=MODEL_DIR)
    args = parser.parse_args(argv)
    result = train(args)
    export(result.pop("net"), args.out)
    meta = {k: v for k, v in result.items()} | {
        "hidden": args.hidden,
        "seed": SEED,
        "rollout_steps": ROLLOUT_STEPS,
        "sequences": args.sequences,
        "epochs": args.epochs,
        "cmu_weight": args.cmu_weight,
        "pose_noise": args.pose_noise,
        "held_out_subjects": list(HELD_OUT_SUBJECTS),
    }
    (args.out / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")
    print(json.dumps(meta, indent=2))
    # The runtime prefers the hand-built fast rollout graph: rebuild it from the new weights too.
    from services.motion import pfnn_onnx

    return pfnn_onnx.main(["--model-dir", str(args.out)])


if __name__ == "__main__":
    raise SystemExit(main())
