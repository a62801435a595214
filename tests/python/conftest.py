"""Fixtures of the Python package's tests (ctest runs them with PYTHONPATH=<build>/python):
the built `hylo` command, and a short simulated session made once per test session, run once
through the command line so that each test compares the package against it."""

import os
import shlex
import subprocess
from pathlib import Path

import numpy as np
import pytest

import hylo

SOURCE_DIR = Path(os.environ.get("HYLO_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PRESET = SOURCE_DIR / "config" / "presets" / "sim_vlp16.yaml"
SIM_DURATION_S = 8  # long enough to leave the IMU's rest; the whole suite stays under a minute


def data_dir():
    """$HYLO_DATA_DIR, else the checkout's default (../shared/data), as the C++ tests."""
    return Path(os.environ.get("HYLO_DATA_DIR") or os.environ.get("HYLO_DEFAULT_DATA_DIR", ""))


def hylo_exe():
    exe = os.environ.get("HYLO_EXE", str(SOURCE_DIR / "build" / "apps" / "hylo"))
    if not os.path.exists(exe):
        pytest.skip(f"the hylo command is not built ({exe}); ctest sets HYLO_EXE")
    return exe


def run_hylo(*args, check=True):
    """Runs `hylo ARGS`; returns the completed process (check: a non-zero exit fails the test)."""
    done = subprocess.run([hylo_exe(), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        pytest.fail(f"hylo {shlex.join(map(str, args))} failed:\n{done.stderr}")
    return done


def cli_error(*args):
    """The one-line reason `hylo ARGS` fails with (after "error: ")."""
    done = run_hylo(*args, check=False)
    assert done.returncode != 0, f"hylo {args} should fail"
    line = done.stderr.strip().splitlines()[-1]
    return line.split("error: ", 1)[1]


def guess_text(truth_path):
    """The first truth pose as the 16 numbers of `--guess`."""
    rows = hylo.read_trajectory(truth_path)
    from hylo._trajectories import poses_from_rows

    return " ".join(f"{v:.17g}" for v in poses_from_rows(rows[:1])[0].ravel())


@pytest.fixture(scope="session")
def sim(tmp_path_factory):
    """`hylo simulate`: sessions A and B of the substation, their truths and the site cloud."""
    out = tmp_path_factory.mktemp("sim")
    run_hylo("simulate", "--out", out, "--duration", SIM_DURATION_S)
    return out


@pytest.fixture(scope="session")
def cli_map(sim, tmp_path_factory):
    """`hylo map` on session A: the output folder."""
    out = tmp_path_factory.mktemp("cli_map")
    run_hylo("map", "--log", sim / "session_a.bag", "--config", PRESET, "--out", out)
    return out


@pytest.fixture(scope="session")
def cli_localize(sim, tmp_path_factory):
    """`hylo localize` of session B in the site cloud from the truth's first pose: the output
    folder and the guess."""
    out = tmp_path_factory.mktemp("cli_localize")
    guess = guess_text(sim / "session_b_truth.tum")
    run_hylo("localize", "--log", sim / "session_b.bag", "--map", sim / "site_reference.pcd",
             "--config", PRESET, "--guess", guess, "--out", out)
    return out, guess


def tum(path):
    return np.loadtxt(path, ndmin=2)
