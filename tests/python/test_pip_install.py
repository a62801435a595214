"""`pip install .` from the checkout, offline, into a venv that takes numpy from Debian, reusing
the build directory: the installed package imports and runs without the build tree's paths.
(A ctest of its own: python_pip_install.)"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import SOURCE_DIR


def test_pip_install_into_a_venv(tmp_path):
    build_dir = os.environ.get("HYLO_BUILD_DIR")
    if not build_dir:
        pytest.skip("HYLO_BUILD_DIR (the build to reuse) is not set; ctest sets it")
    venv = tmp_path / "venv"
    # Debian's pip, seen through --system-site-packages, installs into the venv (no ensurepip).
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", venv],
                   check=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["HYLO_BUILD_DIR"] = build_dir
    install = subprocess.run(
        [python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-deps",
         "--disable-pip-version-check", SOURCE_DIR],
        env=env, cwd=tmp_path, capture_output=True, text=True)
    assert install.returncode == 0, install.stdout + install.stderr
    check = (
        "import hylo, numpy as np, pathlib\n"
        "hylo.write_cloud('c.pcd', np.random.default_rng(0).uniform(0, 10, (2000, 3)))\n"
        "assert hylo.ground_mask(hylo.read_cloud('c.pcd')).shape == (2000,)\n"
        "maps = [l.split()[-1] for l in open('/proc/self/maps') if 'hylo' in l.split()[-1]]\n"
        "print(hylo.__file__); print('\\n'.join(sorted(set(maps))))\n")
    run = subprocess.run([python, "-c", check], env=env, cwd=tmp_path, capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.split()
    package = Path(lines[0]).parent
    assert package.is_relative_to(venv), lines[0]
    loaded = [Path(p) for p in lines[1:]]
    assert any(p.name.startswith("libhylo_run") for p in loaded)
    outside = [p for p in loaded if p.parent != package]
    assert not outside, f"loaded from outside the installed package: {outside}"
