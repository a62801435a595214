"""hylo.slam / hylo.localize give what `hylo map` / `hylo localize` give on the same log."""

import json
import os
import threading
import time

import numpy as np
import pytest

import hylo
from conftest import PRESET, cli_error, run_hylo, tum


def test_slam_is_the_commands_run(sim, cli_map, tmp_path):
    result = hylo.slam(sim / "session_a.bag", PRESET, out=tmp_path)
    expected = tum(cli_map / "trajectory.tum")
    assert result.trajectory.shape == expected.shape and len(expected) > 40
    assert np.abs(result.trajectory - expected).max() <= 1e-9
    assert np.abs(result.live_trajectory - tum(cli_map / "trajectory_live.tum")).max() <= 1e-9
    assert result.t_ns.dtype == np.int64 and np.all(result.t_ns / 1e9 == result.trajectory[:, 0])
    # The same summary (but for timings and memory), and the same files with the same bytes.
    command = json.loads((cli_map / "summary.json").read_text())
    assert result.summary.keys() == command.keys()
    for key in ("mode", "backend", "scans_processed", "counters", "log_read", "path_length_m",
                "map_points", "events"):
        assert result.summary[key] == command[key], key
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(p.name for p in cli_map.iterdir())
    for name in ("trajectory.tum", "trajectory_live.tum", "config.yaml"):
        assert (tmp_path / name).read_bytes() == (cli_map / name).read_bytes(), name
    assert len(result.ms_per_scan) == len(result.trajectory)


@pytest.fixture(scope="module")
def watched_slam(sim, tmp_path_factory):
    """hylo.slam without an output folder, run on a thread from an empty working directory
    while this thread counts how often it gets the GIL, with a progress callable."""
    cwd = tmp_path_factory.mktemp("cwd")
    calls, box = [], {}
    work = threading.Thread(target=lambda: box.update(result=hylo.slam(
        str(sim / "session_a.bag"), hylo.load_config(PRESET),
        progress=lambda done, total: calls.append((done, total)))))
    previous = os.getcwd()
    os.chdir(cwd)
    try:
        start, turns = time.monotonic(), 0
        work.start()
        while work.is_alive():
            time.sleep(0.005)
            turns += 1
        work.join()
    finally:
        os.chdir(previous)
    return box["result"], calls, turns, time.monotonic() - start, cwd


def test_slam_writes_nothing_without_out(watched_slam, cli_map):
    result, _, _, _, cwd = watched_slam
    assert np.abs(result.trajectory - tum(cli_map / "trajectory.tum")).max() <= 1e-9
    assert not any(cwd.iterdir())
    poses = result.poses()
    assert poses.shape == (len(result.trajectory), 4, 4)
    np.testing.assert_allclose(poses[:, :3, 3], result.trajectory[:, 1:4])
    np.testing.assert_allclose(poses[:, :3, :3] @ poses[:, :3, :3].transpose(0, 2, 1),
                               np.broadcast_to(np.eye(3), (len(poses), 3, 3)), atol=1e-9)


def test_slam_releases_the_gil(watched_slam):
    _, _, turns, elapsed, _ = watched_slam
    # Held for the whole run, the GIL would give this thread no turn until the run ended; a
    # loaded machine stretches each 5 ms sleep, so judge the turns against the run's length
    # rather than against a fixed count.
    assert turns >= max(10, 0.25 * elapsed / 0.005), f"{turns} turns in {elapsed:.2f} s"


def test_slam_reports_progress_and_stops_when_the_callback_raises(watched_slam, sim):
    result, calls, _, _, _ = watched_slam
    assert calls and calls[-1] == (result.summary["log_read"]["scan_messages"], 0)
    assert [done for done, _ in calls] == sorted(done for done, _ in calls)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop()

    start = time.monotonic()
    with pytest.raises(Stop):
        hylo.slam(sim / "session_a.bag", PRESET, progress=stop)
    assert time.monotonic() - start < 0.5 * result.summary["elapsed_s"] + 1.0


def test_localize_is_the_commands_run(sim, cli_localize):
    out, guess = cli_localize
    result = hylo.localize(sim / "session_b.bag", sim / "site_reference.pcd", PRESET, guess=guess)
    assert np.abs(result.trajectory - tum(out / "trajectory.tum")).max() <= 1e-9
    command = json.loads((out / "summary.json").read_text())
    assert result.summary["mode"] == "localization"
    assert result.summary["c2c"] == command["c2c"]
    assert result.summary["events"] == command["events"]


def test_missing_files_raise_file_not_found_with_the_commands_message(sim, tmp_path):
    missing = tmp_path / "missing.bag"
    expected = cli_error("map", "--log", missing, "--config", PRESET, "--out", tmp_path / "o")
    with pytest.raises(FileNotFoundError) as raised:
        hylo.slam(missing, PRESET)
    assert str(raised.value) == expected
    with pytest.raises(FileNotFoundError, match="missing.pcd"):
        hylo.localize(sim / "session_b.bag", tmp_path / "missing.pcd", PRESET, guess="0 0 0 0 0 0")


def test_a_log_without_a_trajectory_raises_run_failed(tmp_path):
    # A scan folder whose scans hold too few points: nothing is processed.
    folder = tmp_path / "scans"
    folder.mkdir()
    for k in range(3):
        hylo.write_cloud(folder / f"scan{k}.pcd", np.random.default_rng(k).uniform(-5, 5, (20, 3)))
    config = {"imu": "none"}
    (tmp_path / "c.yaml").write_text("imu: none\n")
    expected = cli_error("map", "--log", folder, "--config", tmp_path / "c.yaml", "--out", tmp_path / "o")
    with pytest.raises(hylo.RunFailed) as raised:
        hylo.slam(folder, config)
    assert str(raised.value) == expected and isinstance(raised.value, ValueError)


def test_bad_arguments_raise_value_or_type_error(sim, tmp_path):
    expected = cli_error("localize", "--log", sim / "session_b.bag", "--map",
                         sim / "site_reference.pcd", "--config", PRESET, "--guess", "1 2 3",
                         "--out", tmp_path / "o")
    with pytest.raises(ValueError) as raised:
        hylo.localize(sim / "session_b.bag", sim / "site_reference.pcd", PRESET, guess="1 2 3")
    assert str(raised.value) == expected
    with pytest.raises(ValueError, match="global_enabled is false"):
        hylo.localize(sim / "session_b.bag", sim / "site_reference.pcd",
                      hylo.load_config(PRESET, {"localization": {"global_enabled": False}}))
    expected = cli_error("localize", "--log", sim / "session_b.bag", "--map",
                         sim / "site_reference.pcd", "--config", PRESET, "--update-after", "-2",
                         "--out", tmp_path / "o")
    with pytest.raises(ValueError) as raised:
        hylo.localize(sim / "session_b.bag", sim / "site_reference.pcd", PRESET, update_after_s=-2)
    assert str(raised.value) == expected.replace("--update-after", "update_after_s")
    with pytest.raises(ValueError, match="update_after_s = nan"):
        hylo.localize(sim / "session_b.bag", sim / "site_reference.pcd", PRESET,
                      update_after_s=float("nan"))
    with pytest.raises(TypeError):
        hylo.slam(42, PRESET)
