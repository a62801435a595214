#!/usr/bin/env bash
# README command 2: installs the dependencies (apt), builds in Release and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
build_dir="${HYLO_BUILD_DIR:-build}"
# --no-tests=error: a run that executes no test is a failure, not a pass.
ctest --test-dir "$build_dir" --output-on-failure --no-tests=error -j"$(nproc)" --timeout 1500
