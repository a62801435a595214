#!/usr/bin/env python3
"""Both estimator back-ends on one log: trajectory errors against the ground truth, a table,
and two figures (trajectories from above; the error of each pose over time).

    python3 examples/python/compare_backends.py --out out/compare
    python3 examples/python/compare_backends.py --log my.bag --config my_robot.yaml \\
        --truth my_truth.tum --out out/compare

Without --log it simulates a 20 s session of the substation with `hylo simulate` (a few seconds)
and uses its truth. Needs the hylo package (docs/python.md) and Debian's python3-matplotlib.
"""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hylo  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
BACKENDS = ("ieskf", "sliding_window")


def hylo_command(given):
    """The `hylo` executable: --hylo, else the checkout's build, else PATH."""
    for candidate in (given, REPO / "build" / "apps" / "hylo", shutil.which("hylo")):
        if candidate and Path(candidate).exists():
            return str(candidate)
    sys.exit("the hylo command was not found: build it (scripts/build.sh hylo) or pass --hylo")


def simulated_log(out, hylo_exe, duration_s):
    sim = out / "sim"
    subprocess.run([hylo_exe, "simulate", "--out", str(sim), "--session", "a", "--duration",
                    str(duration_s), "--no-site"], check=True)
    return sim / "session_a.bag", sim / "session_a_truth.tum", REPO / "config/presets/sim_vlp16.yaml"


def aligned_positions(result, ate):
    """The estimate's positions in the truth's frame (the ATE's SE(3) alignment)."""
    T = ate["T_reference_estimate"]
    return result.trajectory[:, 1:4] @ T[:3, :3].T + T[:3, 3]


def plot(runs, truth, out):
    figure, axes = plt.subplots(figsize=(7, 6))
    axes.plot(truth[:, 1], truth[:, 2], "k--", linewidth=1, label="truth")
    for name, (result, ate, _) in runs.items():
        xyz = aligned_positions(result, ate)
        axes.plot(xyz[:, 0], xyz[:, 1], linewidth=1.2, label=f"{name} (ATE {ate['rmse_m']:.3f} m)")
    axes.set(xlabel="x [m]", ylabel="y [m]", title="trajectories (SE(3)-aligned to the truth)")
    axes.axis("equal")
    axes.legend()
    figure.savefig(out / "trajectories.png", dpi=120, bbox_inches="tight")

    figure, axes = plt.subplots(figsize=(8, 4))
    for name, (_, ate, _) in runs.items():
        axes.plot(ate["t_s"] - ate["t_s"][0], ate["translation_errors_m"], label=name)
    axes.set(xlabel="time [s]", ylabel="position error [m]", title="absolute trajectory error")
    axes.legend()
    figure.savefig(out / "errors.png", dpi=120, bbox_inches="tight")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--log", help="ROS1 bag or scan folder (default: a simulated session)")
    parser.add_argument("--config", help="run configuration (YAML)")
    parser.add_argument("--truth", help="ground truth, TUM")
    parser.add_argument("--out", default="out/compare_backends", help="output folder")
    parser.add_argument("--duration", type=float, default=20.0, help="simulated seconds")
    parser.add_argument("--hylo", help="the hylo executable (to simulate a log)")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.log:
        log, truth_path, config = args.log, args.truth, args.config
        if not config:
            sys.exit("--config is needed with --log")
    else:
        log, truth_path, config = simulated_log(out, hylo_command(args.hylo), args.duration)

    runs = {}
    for backend in BACKENDS:
        result = hylo.slam(log, hylo.load_config(config, overrides={"backend": backend}))
        ate = hylo.eval.ate(result, truth_path) if truth_path else None
        rpe = hylo.eval.rpe(result, truth_path, delta=1.0, delta_unit="m") if truth_path else None
        runs[backend] = (result, ate, rpe)

    print(f"{'back-end':16} {'scans':>6} {'ms/scan':>8} {'ATE [m]':>8} {'RPE/1m [m]':>10} {'RPE [deg]':>9}")
    for name, (result, ate, rpe) in runs.items():
        s = result.summary
        errors = (f"{ate['rmse_m']:8.4f} {rpe['rmse_m']:10.4f} {rpe['rotation_rmse_deg']:9.3f}"
                  if ate else f"{'-':>8} {'-':>10} {'-':>9}")
        print(f"{name:16} {s['scans_processed']:6d} {s['ms_per_scan_median']:8.2f} {errors}")
    if truth_path:
        plot(runs, hylo.read_trajectory(truth_path), out)
        print(f"figures: {out / 'trajectories.png'}, {out / 'errors.png'}")


if __name__ == "__main__":
    main()
