#!/usr/bin/env python3
"""Binding overhead per scan: the Python package against the `hylo` command on the same log.

    PYTHONPATH=build/python python3 tests/python/benchmark_overhead.py [--log BAG --config C]
        [--repeats 5] [--json out/python_overhead.json] [--quick]

Without --log it simulates session A of the substation (20 s; --quick: 6 s, 1 repeat, the ctest
smoke run). Each repeat runs, interleaved so that a busy machine slows all alike:
  cli       `hylo map --log L --config C --out T` in a child process
  slam_out  hylo.slam(L, C, out=T): the same run and the same files, called from Python
  slam      hylo.slam(L, C): the same run, no file written
  pipeline  the log read with hylo.read_log, every IMU sample and scan handed to
            hylo.Pipeline.add_imu / add_scan as numpy arrays, then finish(): the path of data
            that is not in a file (a Python loop, arrays in, a copy into the pipeline's scan)
Figures are medians over the repeats of wall time and CPU time (the process's, or the
child's), per scan. Overheads: slam_out against cli (the whole call), pipeline against slam
(what the Python loop and the arrays add per scan). Printed, and written as JSON.
"""

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import hylo

REPO = Path(__file__).resolve().parents[2]


def child_cpu_s():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(work, child=False):
    """(wall s, CPU s) of work(): this process's CPU, or its children's."""
    cpu = child_cpu_s if child else time.process_time
    wall0, cpu0 = time.perf_counter(), cpu()
    work()
    return time.perf_counter() - wall0, cpu() - cpu0


def feed_pipeline(log, config):
    pipeline = hylo.Pipeline(config)
    for m in hylo.read_log(log, config):
        if isinstance(m, hylo.ImuSample):
            pipeline.add_imu(m.t_s, m.accel, m.gyro, t_ns=m.t_ns)
        else:
            pipeline.add_scan(m.t_s, m.points, m.point_times, m.intensity, m.ring, t_ns=m.t_ns)
    return pipeline.finish()


def hylo_command(given):
    for candidate in (given, REPO / "build" / "apps" / "hylo", shutil.which("hylo")):
        if candidate and Path(candidate).exists():
            return str(candidate)
    sys.exit("the hylo command was not found: pass --hylo")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--log", help="ROS1 bag or scan folder (default: simulated session A)")
    parser.add_argument("--config", default=str(REPO / "config/presets/sim_vlp16.yaml"))
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--quick", action="store_true", help="6 s log, 1 repeat (smoke test)")
    parser.add_argument("--json", help="write the figures here")
    parser.add_argument("--hylo", help="the hylo executable")
    args = parser.parse_args()
    exe = hylo_command(args.hylo)
    repeats = 1 if args.quick else args.repeats
    scratch = Path(tempfile.mkdtemp(prefix="hylo_overhead_"))
    try:
        log = args.log
        if not log:
            subprocess.run([exe, "simulate", "--out", str(scratch / "sim"), "--session", "a",
                            "--duration", "6" if args.quick else "20", "--no-site"], check=True,
                           capture_output=True)
            log = str(scratch / "sim" / "session_a.bag")
        config = hylo.load_config(args.config)
        runs = {
            "cli": (lambda: subprocess.run([exe, "map", "--log", log, "--config", args.config,
                                            "--out", str(scratch / "cli")], check=True,
                                           capture_output=True), True),
            "slam_out": (lambda: hylo.slam(log, config, out=scratch / "py", progress=False), False),
            "slam": (lambda: hylo.slam(log, config, progress=False), False),
            "pipeline": (lambda: feed_pipeline(log, config), False),
        }
        scans = hylo.slam(log, config, progress=False).summary["scans_processed"]  # and warm-up
        samples = {name: [] for name in runs}
        for _ in range(repeats):
            for name, (work, child) in runs.items():
                samples[name].append(timed(work, child))
        figures = {"log": log, "scans": scans, "repeats": repeats}
        for name, values in samples.items():
            walls, cpus = [w for w, _ in values], [c for _, c in values]
            figures[name] = {
                "wall_ms_per_scan": 1e3 * statistics.median(walls) / scans,
                "cpu_ms_per_scan": 1e3 * statistics.median(cpus) / scans,
                # (max - min) / median over the repeats: the noise the overheads sit in
                "wall_spread_percent": 100.0 * (max(walls) - min(walls)) / statistics.median(walls),
                "cpu_spread_percent": 100.0 * (max(cpus) - min(cpus)) / statistics.median(cpus)}
        for name, base in (("slam_out", "cli"), ("pipeline", "slam")):
            figures[f"{name}_over_{base}"] = {
                kind: 100.0 * (figures[name][kind] / figures[base][kind] - 1.0)
                for kind in ("wall_ms_per_scan", "cpu_ms_per_scan")}
    finally:
        shutil.rmtree(scratch, ignore_errors=True)

    print(f"{scans} scans, {repeats} repeat(s), medians per scan")
    print(f"  {'':10} {'wall [ms]':>10} {'CPU [ms]':>10} {'spread wall/CPU':>16}")
    for name in runs:
        f = figures[name]
        print(f"  {name:10} {f['wall_ms_per_scan']:10.3f} {f['cpu_ms_per_scan']:10.3f} "
              f"{f['wall_spread_percent']:7.1f} % {f['cpu_spread_percent']:5.1f} %")
    for key in ("slam_out_over_cli", "pipeline_over_slam"):
        f = figures[key]
        print(f"  {key}: {f['wall_ms_per_scan']:+.1f} % wall, {f['cpu_ms_per_scan']:+.1f} % CPU")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps(figures, indent=2) + "\n")


if __name__ == "__main__":
    main()
