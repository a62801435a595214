"""Trajectories as numpy: (N, 8) rows ``t_s x y z qx qy qz qw`` (TUM's columns), read from and
written to TUM files by the project's own reader and writer."""

import os

import numpy as np

from . import _hylo


def read_trajectory(path):
    """A TUM file as an (N, 8) float64 array. OSError naming the file and line when malformed."""
    rows, _ = read_trajectory_ns(path)
    return rows


def read_trajectory_ns(path):
    """(rows, t_ns): the (N, 8) array and the exact stamps (int64 ns) the file holds."""
    return _hylo._read_trajectory(os.fspath(path))


def write_trajectory(path, trajectory, t_ns=None):
    """Writes (N, 8) rows as a TUM file (whole or not at all); t_ns: exact stamps instead of
    the first column."""
    _hylo._write_trajectory(os.fspath(path), trajectory, t_ns)


def stamped(trajectory):
    """(rows, t_ns or None) of what the evaluation takes: a Result (or anything with
    ``trajectory`` and ``t_ns``), a TUM path, or an (N, 8) array."""
    if hasattr(trajectory, "trajectory") and hasattr(trajectory, "t_ns"):
        return trajectory.trajectory, trajectory.t_ns
    if isinstance(trajectory, (str, os.PathLike)):
        return read_trajectory_ns(trajectory)
    return trajectory, None


def poses_from_rows(rows):
    """(N, 8) rows as (N, 4, 4) homogeneous matrices T_world_body."""
    rows = np.asarray(rows, dtype=float)
    x, y, z, w = rows[:, 4], rows[:, 5], rows[:, 6], rows[:, 7]
    poses = np.zeros((len(rows), 4, 4))
    poses[:, 0, 0] = 1 - 2 * (y * y + z * z)
    poses[:, 0, 1] = 2 * (x * y - z * w)
    poses[:, 0, 2] = 2 * (x * z + y * w)
    poses[:, 1, 0] = 2 * (x * y + z * w)
    poses[:, 1, 1] = 1 - 2 * (x * x + z * z)
    poses[:, 1, 2] = 2 * (y * z - x * w)
    poses[:, 2, 0] = 2 * (x * z - y * w)
    poses[:, 2, 1] = 2 * (y * z + x * w)
    poses[:, 2, 2] = 1 - 2 * (x * x + y * y)
    poses[:, :3, 3] = rows[:, 1:4]
    poses[:, 3, 3] = 1
    return poses
