#!/usr/bin/env bash
# README command 1: installs the dependencies (apt), builds in Release and runs the main job on
# the embedded default, the project's simulated substation (no download): `hylo demo`
# simulates sessions A and B, maps A by SLAM (IESKF), crafts the map, extracts the ground,
# builds the traversability costmap, localizes B in the crafted map with each estimator
# back-end, and ends with the Table I figures and the path of the report.
#   HYLO_DEMO_OUT=DIR   output folder (default out/demo; each run in DIR/<time stamp>, DIR/latest)
#   HYLO_DEMO_QUICK=1   a first look (session B 30 s, coarser lidar: about a minute) instead of
#                       the full run (a few minutes)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh hylo  # the command line alone: the tests are built by scripts/test.sh
args=(--out "${HYLO_DEMO_OUT:-out/demo}")
[ "${HYLO_DEMO_QUICK:-0}" = 1 ] && args+=(--quick)
"${HYLO_BUILD_DIR:-build}/apps/hylo" demo "${args[@]}"
