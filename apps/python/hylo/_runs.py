"""hylo.slam and hylo.localize: one recorded log through the pipeline, as ``hylo map`` and
``hylo localize`` run it (the same C++ run), returning what they write."""

import json
import math
import os
from dataclasses import dataclass

import numpy as np

from . import _hylo
from ._config import load_config
from ._progress import make_progress


@dataclass(frozen=True)
class Result:
    """What a run gives back.

    trajectory:      (N, 8) ``t_s x y z qx qy qz qw``, T_world_imu of the finalized states (the
                     rows of trajectory.tum)
    t_ns:            (N,) int64 exact stamps of those rows, ns
    live_trajectory: (N, 8) the live states (trajectory_live.tum), as a robot had them
    live_t_ns:       (N,) their stamps, ns
    summary:         the dict summary.json holds
    ms_per_scan:     (N,) wall time per processed scan, ms
    """

    trajectory: np.ndarray
    t_ns: np.ndarray
    live_trajectory: np.ndarray
    live_t_ns: np.ndarray
    summary: dict
    ms_per_scan: np.ndarray

    def poses(self):
        """The trajectory as (N, 4, 4) T_world_imu matrices."""
        from ._trajectories import poses_from_rows

        return poses_from_rows(self.trajectory)


def slam(log, config, *, out=None, progress=None):
    """SLAM from scratch on a ROS1 bag or scan folder: ``hylo map --log LOG --config CONFIG``.

    config: a YAML path, a dict of its keys or a hylo.Config. out: also write the command's files
    there (trajectory.tum, odometry.csv, maps, summary.json, ...); none by default. progress: see
    hylo._progress (a bar on a terminal). Raises OSError (unreadable log), ValueError (bad
    configuration) or hylo.RunFailed (no trajectory: the reason)."""
    return _run(log, config, prior_map="", guess=None, update_after_s=None,
                c2c_max_distance_m=0.5, out=out, label="slam", progress=progress)


def localize(log, map, config, guess=None, *, update_after_s=None, c2c_max_distance_m=0.5,
             out=None, progress=None):
    """Localization in a prior map: ``hylo localize --log LOG --map MAP --config CONFIG``.

    map: a PCD/PLY/LAS file or a tiled map directory (world frame). guess: T_world_imu at the
    start as "x y z roll pitch yaw" (m, deg), 6 numbers, 16 numbers or a 4x4 array; None uses
    localization.initial_guess of the configuration, else searches the whole map.
    update_after_s: hybrid mode from that time on (``--update-after``). Other arguments and
    errors as :func:`slam`."""
    return _run(log, config, prior_map=_path(map, "map"), guess=guess,
                update_after_s=update_after_s, c2c_max_distance_m=c2c_max_distance_m, out=out,
                label="localize", progress=progress)


def _run(log, config, prior_map, guess, update_after_s, c2c_max_distance_m, out, label, progress):
    handle = load_config(config)
    if update_after_s is not None and math.isnan(update_after_s):
        raise ValueError("update_after_s = nan: must be -1 (never) or >= 0 s (None: as configured)")
    bar = make_progress(progress, label, "scans")
    try:
        raw = _hylo.run_log(
            log=_path(log, "log"), config=handle, prior_map=prior_map, guess=guess,
            update_after_s=float("nan") if update_after_s is None else float(update_after_s),
            c2c_max_distance_m=float(c2c_max_distance_m),
            out_dir="" if out is None else _path(out, "out"), label=label, progress=bar)
    finally:
        bar.close()
    return Result(trajectory=raw["trajectory"], t_ns=raw["t_ns"],
                  live_trajectory=raw["live_trajectory"], live_t_ns=raw["live_t_ns"],
                  summary=json.loads(raw["summary_json"]), ms_per_scan=raw["ms_per_scan"])


def _path(value, name):
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{name}: expected a path, got {type(value).__name__}")
