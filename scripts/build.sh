#!/usr/bin/env bash
# Configures and builds hylo in Release into ./build (or $HYLO_BUILD_DIR). Incremental.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${HYLO_BUILD_DIR:-build}"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
fi
cmake --build "$build_dir" -j"$(nproc)"
