"""Builds the module `hylo._hylo` with the project's CMake for `pip install .` (pyproject.toml).

The module is built in an existing build directory: $HYLO_BUILD_DIR, else ./build when it is
configured (scripts/build.sh, CI), so nothing is compiled twice; else ./build-python is
configured with only what the module needs. The CMake component `python` then installs the
module, the pure-Python files and the hylo shared libraries side by side into the wheel; they
find one another through $ORIGIN, so the installed package does not need the build directory.
"""

import os
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def build_dir():
    given = os.environ.get("HYLO_BUILD_DIR")
    if given:
        return os.path.abspath(given)
    default = os.path.join(ROOT, "build")
    if os.path.exists(os.path.join(default, "CMakeCache.txt")):
        return default
    return os.path.join(ROOT, "build-python")


def cache_value(build, key):
    with open(os.path.join(build, "CMakeCache.txt"), encoding="utf-8") as cache:
        for line in cache:
            if line.startswith(key + ":"):
                return line.split("=", 1)[1].strip()
    return None


def configure(build):
    """A build directory with what the module needs: no tests, benchmarks or ROS node."""
    command = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
               "-DHYLO_BUILD_TESTS=OFF", "-DHYLO_BUILD_BENCHMARKS=OFF", "-DHYLO_BUILD_ROS=OFF",
               "-DHYLO_BUILD_PYTHON=ON", "-DPython_EXECUTABLE=" + sys.executable]
    if shutil.which("ninja"):
        command += ["-G", "Ninja"]
    if shutil.which("ccache"):
        command += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
    subprocess.check_call(command)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = build_dir()
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            configure(build)
        elif cache_value(build, "HYLO_BUILD_PYTHON") != "ON":
            subprocess.check_call(["cmake", "-DHYLO_BUILD_PYTHON=ON", build])
        subprocess.check_call(["cmake", "--build", build, "--target", "_hylo",
                               "-j", str(os.cpu_count() or 1)])
        module = "_hylo" + sysconfig.get_config_var("EXT_SUFFIX")
        if not os.path.exists(os.path.join(build, "python", "hylo", module)):
            raise RuntimeError(
                f"{build} builds the module for {cache_value(build, 'Python_EXECUTABLE')}, not for "
                f"{sys.executable} ({module} is missing): set HYLO_BUILD_DIR to a new directory")
        # get_ext_fullpath is <build_lib>/hylo/_hylo<suffix>; the component fills <build_lib>/hylo.
        prefix = os.path.dirname(os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name))))
        subprocess.check_call(["cmake", "--install", build, "--component", "python",
                               "--prefix", prefix])


setup(
    ext_modules=[Extension("hylo._hylo", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": os.path.join(build_dir(), "setuptools")}},
)
