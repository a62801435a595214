"""hylo.Pipeline: measurements from memory, scan by scan, through the session the command line
drives (run/session.h). For data that is not in a file: a simulator, a driver, a notebook."""

import json
import os
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _hylo
from ._config import load_config
from ._runs import Result


@dataclass(frozen=True)
class State:
    """The newest processed scan's state (world frame = the prior map's file frame, or the SLAM
    map). Before the first pose, valid is False and the arrays are None.

    status:           initializing | running | lost | failed
    valid:            a pose placed in the map is known and the pipeline is running
    t_s, t_ns:        the scan's end, s and ns
    pose:             4x4 T_world_imu
    velocity:         (3,) of the IMU in the world frame, m/s
    angular_velocity: (3,) in the IMU frame, rad/s
    covariance:       6x6 pose covariance, order [dp (world, m); dtheta (IMU frame, rad)]
    health_good:      the scan fitted the map (the supervisor's health test)
    pose_status:      valid | lost | provisional (a search's frame, not yet the map's)
    """

    status: str
    valid: bool
    t_s: Optional[float] = None
    t_ns: Optional[int] = None
    pose: Optional[np.ndarray] = None
    velocity: Optional[np.ndarray] = None
    angular_velocity: Optional[np.ndarray] = None
    covariance: Optional[np.ndarray] = None
    health_good: bool = False
    pose_status: Optional[str] = None

    @property
    def position(self):
        return None if self.pose is None else self.pose[:3, 3]


class Pipeline(_hylo._Pipeline):
    """The odometry pipeline fed from memory.

    Pipeline(config, prior_map=None, guess=None, keep_history=True): config as for hylo.slam;
    prior_map a cloud file, a tiled map directory or an (N, 3) array (world frame) to localize
    in, with guess as for hylo.localize. keep_history=False keeps no trajectory, results or dense
    map (memory stays flat over a live run; read ``state`` after each scan).

    add_imu(t_s, accel, gyro): one sample (accel m/s^2, gyro rad/s, IMU frame) or arrays of M
    (t (M,), accel and gyro (M, 3)); or a hylo.ImuSample from read_log. t_ns= gives exact
    integer stamps instead of t_s.
    add_scan(t_s, points, point_times=None, intensity=None, ring=None): points (N, 3) in the
    lidar frame (float32 read as is, float64 rounded to float), point_times (N,) s after t_s;
    or a hylo.Scan from read_log. Both return the number of scans the call processed (a scan
    waits until the IMU covers it, and is processed by the add_imu call that does). Both
    release the GIL while the pipeline works. A failed pipeline (e.g. the vehicle moved during
    the IMU initialisation) raises hylo.RunFailed.
    """

    def __init__(self, config, prior_map=None, guess=None, *, keep_history=True):
        if isinstance(prior_map, os.PathLike):
            prior_map = os.fspath(prior_map)
        super().__init__(load_config(config), prior_map, guess, bool(keep_history))

    @property
    def state(self):
        raw = self._state()
        if "t_ns" not in raw:
            return State(status=raw["status"], valid=raw["valid"])
        return State(t_s=raw["t_ns"] / 1e9, **raw)

    @property
    def trajectory(self):
        """(N, 8) finalized states so far, world frame (empty without keep_history)."""
        return self._trajectory(live=False)[0]

    @property
    def live_trajectory(self):
        """(N, 8) live states so far, world frame (empty without keep_history)."""
        return self._trajectory(live=True)[0]

    @property
    def summary(self):
        """Counters, status and sizes so far (the counters of summary.json)."""
        return json.loads(self._summary_json())

    def map(self):
        """(N, 3) the map the estimator registers against, world frame."""
        return self._map(dense=False)

    def dense_map(self):
        """(N, 3) every registered scan at output.dense_map_voxel_m, world frame."""
        return self._map(dense=True)

    def finish(self):
        """The data ended: processes what is left, finalizes every state, returns a Result."""
        self._finish()
        rows, t_ns = self._trajectory(live=False)
        live_rows, live_t_ns = self._trajectory(live=True)
        return Result(trajectory=rows, t_ns=t_ns, live_trajectory=live_rows, live_t_ns=live_t_ns,
                      summary=self.summary, ms_per_scan=np.zeros(0))
