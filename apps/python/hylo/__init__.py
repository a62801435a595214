"""hylo: lidar-inertial localization and offline mapping, from Python.

    import hylo
    result = hylo.slam("session_a.bag", "config/presets/sim_vlp16.yaml")
    print(result.summary["path_length_m"], result.trajectory[-1])    # t x y z qx qy qz qw
    errors = hylo.eval.ate(result, "session_a_truth.tum")
    ground = hylo.ground_mask(hylo.read_cloud("map_dense.pcd"))      # True = ground
    plan = hylo.inspect("map_crafted.pcd", "costmap", "targets.csv")  # viewpoints and route

The calls run the C++ libraries the ``hylo`` command runs, with the same results; see
docs/python.md.
"""

from . import _hylo
from . import eval  # noqa: A004 (hylo.eval, as `hylo eval`)
from ._config import Config, load_config
from ._inspect import InspectionPlan, inspect
from ._pipeline import Pipeline, State
from ._runs import Result, localize, slam
from ._terrain import GroundResult, extract_ground, ground_mask, read_cloud, write_cloud
from ._trajectories import read_trajectory, write_trajectory

ImuSample = _hylo.ImuSample
LogReader = _hylo.LogReader
RunFailed = _hylo.RunFailed
Scan = _hylo.Scan

__version__ = "0.1.0"


def read_log(path, config=None):
    """A ROS1 bag or scan folder, message by message (hylo.ImuSample, hylo.Scan), read with
    the configuration's topics and per-point time convention, as the command reads it."""
    import os

    return LogReader(os.fspath(path), load_config(config))


__all__ = [
    "Config", "GroundResult", "ImuSample", "InspectionPlan", "LogReader", "Pipeline", "Result",
    "RunFailed", "Scan", "State", "eval", "extract_ground", "ground_mask", "inspect",
    "load_config", "localize", "read_cloud", "read_log", "read_trajectory", "slam", "write_cloud",
    "write_trajectory",
]
