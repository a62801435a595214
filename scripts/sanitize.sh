#!/usr/bin/env bash
# Runs the unit tests under sanitizers, each in its own build folder (clang):
#   scripts/sanitize.sh [asan|tsan|all]     (default all)
#   asan  every test (ctest) built with AddressSanitizer + UndefinedBehaviorSanitizer, any
#         report fatal (and LeakSanitizer at exit), in ./build-asan
#   tsan  the tests of the code that runs threads, built with ThreadSanitizer, in ./build-tsan:
#         the ROS node's input queue (callbacks on two threads), concurrent ikd-tree queries,
#         a tiled prior's background loader (TileStreamer),
#         map crafting's MLS workers (std::thread, and PCL's OpenMP loop)
# Prints the wall and CPU time of each part. The long suites (simulated sessions and drives,
# real data, the CLI end to end: `long_tests` below, matched on the test's executable or name)
# are left out of the asan run unless HYLO_SANITIZE_LONG=1. HYLO_SANITIZE_JOBS sets build and
# test parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-all}"
jobs="${HYLO_SANITIZE_JOBS:-$(nproc)}"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

configure() {  # configure <dir> <flags> [cmake args...]
  local dir="$1" flags="$2"
  shift 2
  [ -f "$dir/CMakeCache.txt" ] && return 0
  # -O1 -g without NDEBUG: assertions stay on, reports carry line numbers.
  cmake -S . -B "$dir" "${generator[@]}" "${launcher[@]}" -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DCMAKE_CXX_FLAGS="$flags -fno-omit-frame-pointer" \
    -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" "$@"
}

timed() {  # timed <label> <command...>: runs it, then prints wall and CPU seconds
  local label="$1" start status=0
  shift
  start=$(date +%s)
  local cpu_before
  cpu_before=$(awk '{print $14+$15+$16+$17}' /proc/$$/stat)
  "$@" || status=$?
  local ticks
  ticks=$(($(awk '{print $14+$15+$16+$17}' /proc/$$/stat) - cpu_before))
  echo "[sanitize] $label: $(($(date +%s) - start)) s wall, $((ticks / $(getconf CLK_TCK))) s CPU" \
    "(exit $status)" | tee -a "$summary"
  return "$status"
}

summary=$(mktemp)
trap 'rm -f "$summary"' EXIT
failed=0

if [ "$what" = asan ] || [ "$what" = all ]; then
  # halt_on_error: the first report fails the test; UBSan prints a stack with its report.
  export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_string_checks=1"
  ASAN_OPTIONS+=":detect_stack_use_after_return=1"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  # Benchmarks are left out: their figures mean nothing under a sanitizer.
  configure build-asan "-fsanitize=address,undefined -fno-sanitize-recover=all" \
    -DHYLO_BUILD_BENCHMARKS=OFF
  timed "asan+ubsan build" cmake --build build-asan -j"$jobs" || failed=1
  # Minutes each without a sanitizer, tens of minutes under one.
  long_tests='sim_(odometry|localization|imu_faults|time_offset)_test|sliding_window_sim_test|'
  long_tests+='balm_.*_test|handheld_.*|.*_data_test|.*_site_test|site_mapping_test|'
  long_tests+='demo_quick_test|(mapping|localize|compare)_cli_test|ros_node_integration_test|'
  # Simulated drives judged on accuracy: minutes each, and the smoother's per-scan wall-time
  # budget (real time) does not fit a sanitizer's slowdown, so their figures mean nothing here.
  long_tests+='scenario_matrix_test|tiled_localization_test|'
  long_tests+='install_and_consume|.*_smoke'
  exclude=()
  if [ "${HYLO_SANITIZE_LONG:-0}" != 1 ]; then
    # ctest selects by test name only: the names of the long executables' tests, escaped.
    names=$(ctest --test-dir build-asan --show-only=json-v1 | python3 -c '
import json, os, re, sys
long = re.compile(sys.argv[1])
for t in json.load(sys.stdin)["tests"]:
    exe = os.path.basename((t.get("command") or [""])[0])
    if any(long.fullmatch(n.replace("_NOT_BUILT", "")) for n in (exe, t["name"])):
        print(re.sub(r"([][.*+?^$()|\\])", r"\\\1", t["name"]))' "$long_tests" | paste -sd'|')
    [ -n "$names" ] && exclude=(-E "^($names)\$")
  fi
  timed "asan+ubsan ctest" ctest --test-dir build-asan --output-on-failure --no-tests=error \
    -j"$jobs" --timeout 3000 "${exclude[@]}" || failed=1
fi

if [ "$what" = tsan ] || [ "$what" = all ]; then
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
  # PCL's MLS runs an OpenMP loop: Archer tells ThreadSanitizer about OpenMP's synchronisation.
  archer=$(clang++ -print-file-name=libarcher.so)
  [ -f "$archer" ] && export OMP_TOOL_LIBRARIES="$archer"
  configure build-tsan "-fsanitize=thread" -DHYLO_BUILD_BENCHMARKS=OFF
  tsan_tests=(ikd_tree_test tiles_test craft_test)
  [ -n "$(grep -s 'HYLO_BUILD_ROS:BOOL=ON' build-tsan/CMakeCache.txt)" ] &&
    tsan_tests+=(ros_node_units_test)
  timed "tsan build" cmake --build build-tsan -j"$jobs" --target "${tsan_tests[@]}" || failed=1
  # gtest_discover_tests names tests <Suite>.<Case>: select them by their executables instead.
  timed "tsan tests" bash -c 'status=0; for t in "$@"; do
      exe=$(find build-tsan -type f -name "$t" -perm -u+x | head -n 1)
      echo "[sanitize] $exe"; "$exe" --gtest_brief=1 || status=1; done; exit $status' \
    _ "${tsan_tests[@]}" || failed=1
fi

echo
cat "$summary"
exit "$failed"
