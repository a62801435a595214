#!/usr/bin/env bash
# Installs every build and test dependency of hylo from Debian 12 packages.
# Idempotent: apt skips what is already installed. Run as root (or with sudo available).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libceres-dev libsuitesparse-dev libpcl-dev
  libtbb-dev  # the per-point loops of a scan on more than one core (the `threads` setting)
  libyaml-cpp-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev libnanoflann-dev
  nlohmann-json3-dev libpng-dev liblzf-dev
  librosbag-storage-dev libroscpp-dev libroscpp-core-dev
  libbz2-dev libroslz4-dev  # chunks of bags read without their index (both come with rosbag)
  # ROS 2 recordings (hylo::logs): rosbag2 sqlite3 storage, MCAP chunks and rosbag2's own
  # compression (zstd; lz4 frames)
  libsqlite3-dev libzstd-dev liblz4-dev
  libsensor-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libstd-msgs-dev
  # ROS1 node (apps/ros) and its integration test: tf2_ros, std_srvs; roscore + rosbag play
  libtf2-ros-dev libstd-srvs-dev ros-core
  python3-std-srvs python3-nav-msgs python3-sensor-msgs  # rostopic/rosservice on its types
  gnuplot-nox
  # the Python package (apps/python, `pip install .`), its tests and examples
  pybind11-dev python3-pybind11 python3-dev python3-numpy python3-pytest python3-matplotlib
  python3-setuptools python3-pip python3-venv
  clang libclang-rt-dev  # scripts/fuzz.sh, scripts/sanitize.sh: libFuzzer, sanitizer runtimes
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "[setup] all ${#packages[@]} Debian packages already installed"
  exit 0
fi
echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
