"""Evaluate the locomotion network on people it never saw: foot sliding, speed, and a gait distance.

Usage:
    .venv/bin/python eval/gait.py [--quick] [--json PATH] [--before-model DIR] [--model DIR]

Held-out people: CMU subjects 2, 5 and 12 of ../shared/data/cmu_locomotion_daz (walks and a jog, 26 s;
services.motion.train_locomotion.HELD_OUT_SUBJECTS keeps them out of training). Each take is retargeted
to our skeleton (the captured gait), and its root path (every 10th frame as waypoints) and mean speed are
given to the controller (the generated gait, feet locked as synthesis does).

Metrics:
    foot_slide_cm: cm per frame that a foot the network calls planted moves horizontally (after foot
        locking, what the pipeline shows); foot_slide_raw_cm before locking.
    speed_error_m_s: |network's own root speed - commanded speed| over the cruising frames (the root
        follows the plan exactly; this says whether the gait the network chose carries the body at that
        speed), per held-out take and on straight walks/runs at 0.7, 1.0, 1.4, 2.0 and 3.0 m/s.
    gait_fd_heldout: Frechet distance between windowed joint-velocity features of generated and captured
        gait, the current network; gait_fd_before: the same for the network before the Daz takes were
        added (models kept under --before-model; without it the number recorded below is reported).

Features (the same code for generated and captured motion): joint velocities in the character's heading
frame (m/s; x sideways, y up, z forward; the frame moves with the hips' ground point) of Head, both hands,
both knees (LeftLeg/RightLeg) and both ankles (LeftFoot/RightFoot), and the hips' vertical velocity (their
x, z are 0 in that frame), over 1 s windows (30 frames) every 3 frames where the root moves at >= 0.3 m/s
on average; each window gives the mean and the standard deviation of each of the 22 velocity components
(44 numbers). Frechet distance: |mu_g - mu_c|^2 + tr(S_g + S_c - 2 (S_g S_c)^1/2) over those windows.

Decomposition (what dominates the distance): the mean term is a sum over features and so is the covariance
term's trace, so each feature's (mu_g - mu_c)_i^2 + (S_g + S_c - 2 (S_g S_c)^1/2)_ii is its exact share of
the distance. gait_fd_by_joint sums them per feature joint (mean_term, cov_term; mean_features: the windows'
mean velocities, std_features: their spread), gait_fd_top_features lists the features carrying most, and
each take's own FD (its generated against its captured windows) is in takes[].fd.

Targets: gait_fd_heldout <= gait_fd_before / 2; foot_slide_cm <= 0.5.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy import linalg

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from services.motion.ik import global_transforms  # noqa: E402
from services.motion.locomotion import PfnnRuntime, lock_walk, locomote, runtime  # noqa: E402
from services.motion.locomotion_features import to_local  # noqa: E402
from services.motion.train_locomotion import (  # noqa: E402
    SHARED,
    annotate,
    daz_clip,
    daz_heldout_rows,
    plausible,
)
from wana.domain.skeleton import JOINT_INDEX  # noqa: E402
from wana.domain.units import FPS  # noqa: E402

# gait_fd_before as measured on the network committed before the Daz takes (models/locomotion at 53ddc0f),
# `eval/gait.py --json ... --before-model /tmp/gait-before/locomotion`: used when --before-model is not given.
# 0.7412 with the runtime of that time; 0.7854 through today's (its poses low-passed and the feet locked with
# one frame of blend, services.motion.locomotion.lock_walk, as every network's now are).
RECORDED_FD_BEFORE = 0.7854
FEATURE_JOINTS = ("Hips", "Head", "LeftHand", "RightHand", "LeftLeg", "RightLeg", "LeftFoot", "RightFoot")
WINDOW = 30
HOP = 3
MIN_SPEED = 0.3
SWEEP_SPEEDS = (0.7, 1.0, 1.4, 2.0, 3.0)


def velocity_windows(root: np.ndarray, rotations: np.ndarray, heading: np.ndarray) -> np.ndarray:
    """(N, 48) window features of one motion (see the module docstring)."""
    pos, _ = global_transforms(rotations, root)
    local = to_local(pos[:, [JOINT_INDEX[j] for j in FEATURE_JOINTS]], root[:, [0, 2]], heading)
    vel = np.delete(np.diff(local, axis=0).reshape(len(local) - 1, -1), [0, 2], axis=1) * FPS  # hips' x, z: 0
    speed = np.linalg.norm(np.diff(root[:, [0, 2]], axis=0), axis=1) * FPS
    out = []
    for s in range(0, len(vel) - WINDOW + 1, HOP):
        if speed[s : s + WINDOW].mean() >= MIN_SPEED:
            w = vel[s : s + WINDOW]
            out.append(np.concatenate([w.mean(0), w.std(0)]))
    return np.asarray(out).reshape(-1, 2 * vel.shape[1])


def frechet_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Frechet distance between Gaussians fitted to the rows of a and b."""
    mu_a, mu_b = a.mean(0), b.mean(0)
    s_a, s_b = np.cov(a, rowvar=False), np.cov(b, rowvar=False)
    covmean = linalg.sqrtm(s_a @ s_b)
    if np.iscomplexobj(covmean):
        covmean = covmean.real
    return float(np.sum((mu_a - mu_b) ** 2) + np.trace(s_a + s_b - 2 * covmean))


def feature_names() -> list[str]:
    """Names of the 44 window features: "mean:Head.y", "std:LeftFoot.z", ... (velocity_windows' order)."""
    comps = [f"{j}.{a}" for j in FEATURE_JOINTS for a in "xyz" if not (j == "Hips" and a != "y")]
    return [f"{stat}:{c}" for stat in ("mean", "std") for c in comps]


def frechet_terms(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-feature mean term (mu_a - mu_b)^2 and covariance term (S_a + S_b - 2 (S_a S_b)^1/2)_ii.

    Both are exact: their sum over all features is frechet_distance(a, b) (the trace is the sum of the
    diagonal), so a feature's share says how much of the distance it carries.
    """
    mu_a, mu_b = a.mean(0), b.mean(0)
    s_a, s_b = np.cov(a, rowvar=False), np.cov(b, rowvar=False)
    covmean = linalg.sqrtm(s_a @ s_b)
    if np.iscomplexobj(covmean):
        covmean = covmean.real
    return (mu_a - mu_b) ** 2, np.diag(s_a + s_b - 2 * covmean)


def fd_by_joint(gen: np.ndarray, cap: np.ndarray) -> dict[str, dict[str, float]]:
    """The Frechet distance split by feature joint into its mean and covariance terms, and within each
    into the windows' mean-velocity and velocity-spread (std) features; the rows sum to the FD."""
    mean_t, cov_t = frechet_terms(gen, cap)
    names = feature_names()
    out: dict[str, dict[str, float]] = {}
    for j in FEATURE_JOINTS:
        idx = [i for i, n in enumerate(names) if n.split(":")[1].split(".")[0] == j]
        row = {"mean_term": float(mean_t[idx].sum()), "cov_term": float(cov_t[idx].sum())}
        for stat in ("mean", "std"):
            k = [i for i in idx if names[i].startswith(stat + ":")]
            row[f"{stat}_features"] = float(mean_t[k].sum() + cov_t[k].sum())
        row["total"] = row["mean_term"] + row["cov_term"]
        out[j] = {k: round(v, 4) for k, v in row.items()}
    return out


def top_features(gen: np.ndarray, cap: np.ndarray, n: int = 8) -> list[dict]:
    """The n features carrying most of the distance, with the generated and captured means and spreads."""
    mean_t, cov_t = frechet_terms(gen, cap)
    names = feature_names()
    order = np.argsort(-(mean_t + cov_t))[:n]
    return [
        {
            "feature": names[i],
            "share": round(float((mean_t[i] + cov_t[i]) / (mean_t.sum() + cov_t.sum())), 4),
            "mean_term": round(float(mean_t[i]), 4),
            "cov_term": round(float(cov_t[i]), 4),
            "generated_mean": round(float(gen[:, i].mean()), 4),
            "captured_mean": round(float(cap[:, i].mean()), 4),
            "generated_sd": round(float(gen[:, i].std()), 4),
            "captured_sd": round(float(cap[:, i].std()), 4),
        }
        for i in order
    ]


def foot_slide(pos: np.ndarray, contacts: np.ndarray) -> list[float]:
    """Per-frame horizontal ankle displacement (cm) while that foot is planted on both frames."""
    out: list[float] = []
    for k, name in enumerate(("LeftFoot", "RightFoot")):
        f = pos[:, JOINT_INDEX[name]][:, [0, 2]]
        both = (contacts[1:, k] > 0) & (contacts[:-1, k] > 0)
        out.extend((np.linalg.norm(np.diff(f, axis=0), axis=1)[both] * 100).tolist())
    return out


def generate(track: np.ndarray, speed: float, rollout) -> dict:  # noqa: ANN001 - a RolloutRuntime
    """The controller walking a captured ground track at its speed: root, locked rotations, raw/locked slides."""
    heading0 = float(np.arctan2(*(track[min(10, len(track) - 1)] - track[0])))
    loco = locomote(track[::10] if len(track) > 10 else track[[0, -1]], speed, heading0, rollout=rollout)
    locked = lock_walk(loco.rotations, loco.root_position, loco.contacts)
    pos_raw, _ = global_transforms(loco.rotations, loco.root_position)
    pos, _ = global_transforms(locked, loco.root_position)
    cruise = loco.network_speed is not None and np.any(_cruising(loco))
    return {
        "root": loco.root_position,
        "rotations": locked,
        "heading": loco.heading,
        "slide": foot_slide(pos, loco.contacts),
        "slide_raw": foot_slide(pos_raw, loco.contacts),
        "network_speed": float(np.mean(loco.network_speed[_cruising(loco)])) if cruise else float("nan"),
    }


def _cruising(loco) -> np.ndarray:  # noqa: ANN001 - Locomotion
    v = np.zeros(len(loco.root_position))
    v[1:] = np.linalg.norm(np.diff(loco.root_position[:, [0, 2]], axis=0), axis=1) * FPS
    return v >= 0.9 * v.max()


def straight_speed_errors(rollout) -> dict[str, float]:  # noqa: ANN001 - a RolloutRuntime
    """|network speed - commanded| on an 8 m straight line at each sweep speed."""
    out = {}
    for v in SWEEP_SPEEDS:
        g = generate(np.stack([np.zeros(81), np.linspace(0, 8, 81)], -1), v, rollout)
        out[f"{v:.1f}"] = round(abs(g["network_speed"] - v), 4)
    return out


def evaluate(rollout, rows: list[dict]) -> dict:  # noqa: ANN001 - a RolloutRuntime
    """Per-take results and the pooled features of one network on the held-out takes."""
    gen_f, cap_f, slides, slides_raw, takes = [], [], [], [], []
    for r in rows:
        root, rot = daz_clip(SHARED / "cmu_locomotion_daz" / r["file"])
        if not plausible(root):
            continue
        _, _, heading, _, _, _ = annotate(root, rot)
        track = root[:, [0, 2]]
        speed = float(np.linalg.norm(np.diff(track, axis=0), axis=1).mean() * FPS)
        g = generate(track, speed, rollout)
        cap_f.append(velocity_windows(root, rot, heading))
        gen_f.append(velocity_windows(g["root"], g["rotations"], g["heading"]))
        m_t, c_t = (
            frechet_terms(gen_f[-1], cap_f[-1])
            if min(len(gen_f[-1]), len(cap_f[-1])) > 1
            else (
                np.full(1, np.nan),
                np.full(1, np.nan),
            )
        )
        slides += g["slide"]
        slides_raw += g["slide_raw"]
        takes.append(
            {
                "take": r["file"],
                "description": r["description"],
                "speed_m_s": round(speed, 3),
                "speed_error_m_s": round(abs(g["network_speed"] - speed), 4),
                "foot_slide_cm": round(float(np.mean(g["slide"] or [0])), 4),
                # this take's generated windows against its own captured ones (few windows: a rough guide)
                "fd": round(float(m_t.sum() + c_t.sum()), 4),
                "fd_mean_term": round(float(m_t.sum()), 4),
                "fd_cov_term": round(float(c_t.sum()), 4),
            }
        )
    gen, cap = np.concatenate(gen_f), np.concatenate(cap_f)
    mean_t, cov_t = frechet_terms(gen, cap)
    return {
        "fd": frechet_distance(gen, cap),
        "fd_mean_term": float(mean_t.sum()),
        "fd_cov_term": float(cov_t.sum()),
        "fd_by_joint": fd_by_joint(gen, cap),
        "fd_top_features": top_features(gen, cap),
        "windows_generated": len(gen),
        "windows_captured": len(cap),
        "foot_slide_cm": float(np.mean(slides)) if slides else 0.0,
        "foot_slide_raw_cm": float(np.mean(slides_raw)) if slides_raw else 0.0,
        "speed_error_m_s": float(np.mean([t["speed_error_m_s"] for t in takes])),
        "takes": takes,
    }


def print_decomposition(result: dict) -> None:
    """The FD by joint (mean and covariance terms; mean-velocity and spread features) and its top features."""
    fd = result["gait_fd_heldout"]
    print(
        f"\n{'joint':10s} {'total':>7s} {'share':>6s} {'mean t':>7s} {'cov t':>7s} {'mean f':>7s} {'std f':>7s}"
    )
    for j, r in sorted(result["gait_fd_by_joint"].items(), key=lambda kv: -kv[1]["total"]):
        print(
            f"{j:10s} {r['total']:7.4f} {r['total'] / fd:6.1%} {r['mean_term']:7.4f} {r['cov_term']:7.4f}"
            f" {r['mean_features']:7.4f} {r['std_features']:7.4f}"
        )
    print(f"\n{'feature':18s} {'share':>6s} {'mean t':>7s} {'cov t':>7s}  generated (mean, sd)  captured")
    for f in result["gait_fd_top_features"]:
        print(
            f"{f['feature']:18s} {f['share']:6.1%} {f['mean_term']:7.4f} {f['cov_term']:7.4f}"
            f"  {f['generated_mean']:7.3f} {f['generated_sd']:6.3f}    {f['captured_mean']:7.3f} {f['captured_sd']:6.3f}"
        )
    print()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="skip the straight-line speed sweep (< 30 s)")
    parser.add_argument("--json", type=Path, default=None, help="write the metrics here")
    parser.add_argument(
        "--before-model", type=Path, default=None, help="models/locomotion of the old network"
    )
    parser.add_argument(
        "--model", type=Path, default=None, help="evaluate this model folder (default: the shipped one)"
    )
    args = parser.parse_args(argv)
    t0 = time.time()
    rows = daz_heldout_rows()
    rt = PfnnRuntime(args.model) if args.model else runtime()
    why = (
        f"no held-out takes under {SHARED / 'cmu_locomotion_daz'}"
        if not rows
        else "no locomotion network (models/locomotion or onnxruntime missing)"
        if rt is None
        else ""
    )
    if why:  # `make eval` runs on machines without ../shared/data: say so, do not fail
        print(f"{why}: nothing to evaluate")
        if args.json:
            args.json.parent.mkdir(parents=True, exist_ok=True)
            skipped = {"gait_fd_heldout": None, "gait_fd_before": RECORDED_FD_BEFORE, "skipped": why}
            args.json.write_text(json.dumps(skipped, indent=2) + "\n")
        return 0
    now = evaluate(rt, rows)
    before = evaluate(PfnnRuntime(args.before_model), rows) if args.before_model else None
    result = {
        "gait_fd_heldout": round(now["fd"], 4),
        "gait_fd_before": round(before["fd"], 4) if before else RECORDED_FD_BEFORE,
        "gait_fd_before_source": str(args.before_model) if before else "recorded in eval/gait.py",
        "gait_fd_mean_term": round(now["fd_mean_term"], 4),
        "gait_fd_cov_term": round(now["fd_cov_term"], 4),
        "gait_fd_by_joint": now["fd_by_joint"],
        "gait_fd_top_features": now["fd_top_features"],
        "foot_slide_cm": round(now["foot_slide_cm"], 4),
        "foot_slide_raw_cm": round(now["foot_slide_raw_cm"], 4),
        "speed_error_m_s": round(now["speed_error_m_s"], 4),
        "speed_error_straight_m_s": None if args.quick else straight_speed_errors(rt),
        "windows_generated": now["windows_generated"],
        "windows_captured": now["windows_captured"],
        "takes": now["takes"],
        "held_out_subjects": sorted({int(r["subject"]) for r in rows}),
        "seconds": 0.0,
    }
    if before:
        result |= {
            "foot_slide_cm_before": round(before["foot_slide_cm"], 4),
            "foot_slide_raw_cm_before": round(before["foot_slide_raw_cm"], 4),
            "speed_error_m_s_before": round(before["speed_error_m_s"], 4),
            "gait_fd_by_joint_before": before["fd_by_joint"],
            "speed_error_straight_m_s_before": None
            if args.quick
            else straight_speed_errors(PfnnRuntime(args.before_model)),
        }
    result["seconds"] = round(time.time() - t0, 2)
    tables = ("takes", "gait_fd_by_joint", "gait_fd_top_features", "gait_fd_by_joint_before")
    for k, v in result.items():
        if k not in tables:
            print(f"{k:32s} {v}")
    print_decomposition(result)
    for t in result["takes"]:
        print(
            f"  {t['take']:18s} {t['description']:10s} {t['speed_m_s']:.2f} m/s  speed err {t['speed_error_m_s']:.3f}"
            f"  slide {t['foot_slide_cm']:.3f} cm  take FD {t['fd']:.3f} (mean {t['fd_mean_term']:.3f})"
        )
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
