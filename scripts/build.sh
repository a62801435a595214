#!/usr/bin/env bash
# Configures (once) and builds hylo in Release into ./build (or $HYLO_BUILD_DIR). Incremental.
#   scripts/build.sh               everything: libraries, tools, tests, benchmarks
#   scripts/build.sh TARGET...     only those targets and what they need (e.g. `hylo`)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${HYLO_BUILD_DIR:-build}"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# ccache, when the machine has it, makes rebuilds in another checkout cheap; CI has none.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release
fi
targets=()
[ "$#" -gt 0 ] && targets=(--target "$@")
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}"
