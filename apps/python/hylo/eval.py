"""Trajectory errors: what ``hylo eval ate|rpe`` computes, under its JSON keys.

Each trajectory is a hylo Result, a TUM file, or an (N, 8) array ``t_s x y z qx qy qz qw``.
The estimate is paired with the reference in time by interpolating the reference (default) or
by the nearest stamp within max_dt_s. Bad input raises ValueError with the command's message.
"""

from . import _hylo
from ._trajectories import stamped


def ate(est, gt, align="se3", *, association="interp", max_dt_s=0.02, max_gap_s=1.0):
    """Absolute trajectory error after alignment (se3, sim3, first, none): a dict with the keys of
    ``hylo eval ate --json`` (rmse_m, mean_m, ..., T_reference_estimate as 4x4), plus ``t_s`` and
    ``translation_errors_m``, the error of each pair for plots."""
    est_rows, est_t_ns = stamped(est)
    gt_rows, gt_t_ns = stamped(gt)
    return _hylo._ate(est_rows, est_t_ns, gt_rows, gt_t_ns, align=align, association=association,
                      max_dt_s=float(max_dt_s), max_gap_s=float(max_gap_s))


def rpe(est, gt, delta=1.0, delta_unit="frames", *, association="interp", max_dt_s=0.02,
        max_gap_s=1.0):
    """Relative pose error over pairs ``delta`` frames (or metres, delta_unit="m") apart: a dict
    with the keys of ``hylo eval rpe --json``."""
    est_rows, est_t_ns = stamped(est)
    gt_rows, gt_t_ns = stamped(gt)
    return _hylo._rpe(est_rows, est_t_ns, gt_rows, gt_t_ns, delta=float(delta),
                      delta_unit=delta_unit, association=association, max_dt_s=float(max_dt_s),
                      max_gap_s=float(max_gap_s))
