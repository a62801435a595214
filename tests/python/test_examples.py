"""examples/python run end to end and write their figures. (A ctest of its own:
python_examples.)"""

import subprocess
import sys

import pytest

import hylo
from conftest import SOURCE_DIR, hylo_exe
from test_ground import site

pytest.importorskip("matplotlib")
EXAMPLES = SOURCE_DIR / "examples" / "python"


def run(script, *args):
    done = subprocess.run([sys.executable, EXAMPLES / script, *map(str, args)], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_compare_backends_on_a_simulated_log(tmp_path):
    out = run("compare_backends.py", "--out", tmp_path, "--duration", 8, "--hylo", hylo_exe())
    assert "ieskf" in out and "sliding_window" in out
    assert (tmp_path / "trajectories.png").stat().st_size > 0
    assert (tmp_path / "errors.png").stat().st_size > 0


def test_ground_filter_on_a_cloud(tmp_path):
    hylo.write_cloud(tmp_path / "site.pcd", site())
    run("ground_filter.py", tmp_path / "site.pcd", "--threshold", 0.1, "--out", tmp_path / "out")
    ground = hylo.read_cloud(tmp_path / "out" / "ground.pcd")
    objects = hylo.read_cloud(tmp_path / "out" / "objects.pcd")
    assert len(ground) + len(objects) == len(site()) and len(objects) > 0
    assert (tmp_path / "out" / "ground.png").stat().st_size > 0
