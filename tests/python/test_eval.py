"""hylo.eval.ate / rpe compute what `hylo eval ate|rpe` prints, under its JSON keys."""

import json

import numpy as np
import pytest

import hylo
from conftest import run_hylo


def command(tmp_path, metric, est, gt, *options):
    run_hylo("eval", metric, "--est", est, "--gt", gt, "--json", tmp_path / "e.json", *options)
    return json.loads((tmp_path / "e.json").read_text())


@pytest.mark.parametrize("align", ["se3", "sim3", "first", "none"])
def test_ate_is_the_commands(sim, cli_map, tmp_path, align):
    est, gt = cli_map / "trajectory.tum", sim / "session_a_truth.tum"
    expected = command(tmp_path, "ate", est, gt, "--align", align)
    ate = hylo.eval.ate(est, gt, align=align)
    for key, value in expected.items():
        if key in ("estimate", "reference", "format", "max_dt_s", "max_gap_s"):
            continue
        if isinstance(value, str):
            assert ate[key] == value, key
        else:
            np.testing.assert_allclose(np.ravel(ate[key]), np.ravel(value), rtol=1e-12, err_msg=key)
    assert ate["T_reference_estimate"].shape == (4, 4)
    assert len(ate["translation_errors_m"]) == ate["num_poses"] == len(ate["t_s"])


def test_rpe_is_the_commands_and_arrays_work_as_files(sim, cli_map, tmp_path):
    est, gt = cli_map / "trajectory.tum", sim / "session_a_truth.tum"
    expected = command(tmp_path, "rpe", est, gt, "--delta", "0.5", "--delta-unit", "m")
    rpe = hylo.eval.rpe(est, gt, delta=0.5, delta_unit="m")
    for key in ("num_poses", "num_pairs", "rmse_m", "rotation_rmse_deg", "max_m"):
        assert rpe[key] == pytest.approx(expected[key], rel=1e-12), key
    # (N, 8) arrays: stamps rounded from seconds; the same errors to well below a micrometre.
    from_arrays = hylo.eval.rpe(hylo.read_trajectory(est), hylo.read_trajectory(gt), delta=0.5,
                                delta_unit="m")
    assert from_arrays["rmse_m"] == pytest.approx(rpe["rmse_m"], abs=1e-7)


def test_trajectories_round_trip_through_tum(cli_map, tmp_path):
    rows, t_ns = hylo._trajectories.read_trajectory_ns(cli_map / "trajectory.tum")
    hylo.write_trajectory(tmp_path / "t.tum", rows, t_ns=t_ns)
    again, again_t_ns = hylo._trajectories.read_trajectory_ns(tmp_path / "t.tum")
    np.testing.assert_array_equal(again, rows)
    np.testing.assert_array_equal(again_t_ns, t_ns)
    # Stamps and positions as the file has them (the reader normalises the quaternions).
    np.testing.assert_array_equal(rows[:, :4], np.loadtxt(cli_map / "trajectory.tum")[:, :4])


def test_bad_input_raises(cli_map, tmp_path):
    est = hylo.read_trajectory(cli_map / "trajectory.tum")
    with pytest.raises(ValueError, match="align: 'umeyama' is not one of se3, sim3, first, none"):
        hylo.eval.ate(est, est, align="umeyama")
    with pytest.raises(ValueError, match=r"est \(t_s x y z qx qy qz qw\): expected shape \(N, 8\)"):
        hylo.eval.ate(est[:, :7], est)
    with pytest.raises(ValueError, match="gt: holds no pose"):
        hylo.eval.ate(est, np.zeros((0, 8)))
    with pytest.raises(ValueError, match="ate: "):
        hylo.eval.ate(est[:2], est[:2])  # SE(3) alignment needs 3 poses
    bad = est.copy()
    bad[3, 7] = 5.0
    with pytest.raises(ValueError, match="est row 3: .*unit norm"):
        hylo.eval.rpe(bad, est)
    with pytest.raises(ValueError, match="delta_unit: 's' is not one of frames, m"):
        hylo.eval.rpe(est, est, delta_unit="s")
    (tmp_path / "bad.tum").write_text("1 2 3\n")
    with pytest.raises(OSError, match="bad.tum"):
        hylo.read_trajectory(tmp_path / "bad.tum")
