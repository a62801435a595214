"""hylo.read_log: a log as the command reads it, and its errors."""

import numpy as np
import pytest

import hylo
from conftest import PRESET, cli_error


def test_scans_are_views_into_the_log_message(sim):
    reader = hylo.read_log(sim / "session_a.bag", PRESET)
    scan = next(m for m in reader if isinstance(m, hylo.Scan))
    points = scan.points
    assert points.dtype == np.float32 and points.shape == (len(scan), 3) and not points.flags.owndata
    assert scan.offsets_ns.dtype == np.int32 and scan.ring.dtype == np.uint16
    np.testing.assert_array_equal(scan.point_times, scan.offsets_ns / 1e9)
    assert scan.end_t_s >= scan.t_s and abs(scan.t_ns / 1e9 - scan.t_s) < 1e-6
    del scan  # the view keeps the scan alive
    assert np.isfinite(points).all()


def test_unreadable_logs_raise_os_error_with_the_commands_message(sim, tmp_path):
    missing = tmp_path / "missing.bag"
    with pytest.raises(FileNotFoundError) as raised:
        hylo.read_log(missing)
    assert str(raised.value) == cli_error("map", "--log", missing, "--config", PRESET, "--out",
                                          tmp_path / "o")
    config = hylo.load_config(PRESET, {"lidar": {"topic": "/nope"}})
    (tmp_path / "c.yaml").write_text(config.text)
    expected = cli_error("map", "--log", sim / "session_a.bag", "--config", tmp_path / "c.yaml",
                         "--out", tmp_path / "o")
    with pytest.raises(OSError) as raised:
        hylo.read_log(sim / "session_a.bag", config)
    assert str(raised.value) == expected
    (tmp_path / "junk.bag").write_bytes(b"#ROSBAG V2.0\n" + b"\0" * 64)
    with pytest.raises(OSError, match="junk.bag"):
        list(hylo.read_log(tmp_path / "junk.bag", PRESET))
