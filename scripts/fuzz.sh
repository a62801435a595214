#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, tests/fuzz) in ./build-fuzz and runs each
# for a given time, one after the other, then prints one line per target: executions,
# coverage (libFuzzer's final cov/ft), corpus size and the findings (crashes, timeouts > 1 s,
# out-of-memory, leaks). Exit status 1 when anything was found.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]     (default 60 s, every target)
# HYLO_FUZZ_RUNS=N also stops a target after N executions, whichever comes first (the issue's
# bar is 10 minutes or 1 M executions: HYLO_FUZZ_RUNS=1000000 scripts/fuzz.sh 600).
# HYLO_FUZZ_SUMMARY names the summary file (default <build dir>/fuzz_summary.txt), so that two
# runs over different targets can share the build.
# The grown corpora stay in build-fuzz/corpus/<target> (a rerun continues from them); findings
# go to build-fuzz/findings/<target>/<run time>/. Reproduce one: build-fuzz/tests/fuzz/hylo_fuzz_<target>
# <file>; once the reader is fixed, copy the file to tests/fuzz/regressions/<target>/ so that
# ctest replays it. HYLO_FUZZ_BUILD_DIR overrides the build folder, HYLO_FUZZ_JOBS the build's
# parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
all_targets=(bag_pointcloud2 bag_imu bag_records mcap_records cdr_messages rosbag2_metadata pcd ply
  kitti_bin las trajectory scan_folder pose_guess run_config json)
targets=("$@")
[ "${#targets[@]}" -eq 0 ] && targets=("${all_targets[@]}")
build_dir="${HYLO_FUZZ_BUILD_DIR:-build-fuzz}"

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  # -O1 -g without NDEBUG: Eigen's and the code's assertions stay on while fuzzing.
  cmake -S . -B "$build_dir" "${generator[@]}" "${launcher[@]}" \
    -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DHYLO_BUILD_FUZZERS=ON -DHYLO_BUILD_TESTS=OFF -DHYLO_BUILD_BENCHMARKS=OFF \
    -DHYLO_BUILD_ROS=OFF
fi
cmake --build "$build_dir" -j"${HYLO_FUZZ_JOBS:-$(nproc)}" --target hylo_fuzzers
"$build_dir/tests/fuzz/hylo_fuzz_make_seeds" "$build_dir/seeds" >/dev/null

# One line of libFuzzer's log: the value after `key` on the last line that has it.
last_value() { grep -o "$2 *[0-9]*" "$1" | tail -n 1 | grep -o '[0-9]*$' || echo "-"; }

summary="${HYLO_FUZZ_SUMMARY:-$build_dir/fuzz_summary.txt}"
printf '%-16s %6s %12s %8s %6s %7s %6s %7s %8s %5s %5s %s\n' target seconds executions \
  exec/s cov ft corpus crashes timeouts ooms leaks status >"$summary"
found=0
for t in "${targets[@]}"; do
  corpus="$build_dir/corpus/$t"
  findings="$build_dir/findings/$t/$(date +%Y%m%d-%H%M%S)"
  log="$build_dir/logs/$t.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")"
  extra=()
  [ "$t" = run_config ] && extra=(config)
  [ -d "tests/fuzz/corpus/$t" ] && extra+=("tests/fuzz/corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && extra+=("tests/fuzz/regressions/$t")
  [ -n "${HYLO_FUZZ_RUNS:-}" ] && extra_flags=(-runs="$HYLO_FUZZ_RUNS") || extra_flags=()
  dict=()
  [ -f "tests/fuzz/dict/$t.dict" ] && dict=(-dict="tests/fuzz/dict/$t.dict")
  echo "[fuzz] $t for ${seconds} s (log: $log)"
  start=$(date +%s)
  status=ok
  # The first folder receives new inputs; the others are read-only seeds.
  "$build_dir/tests/fuzz/hylo_fuzz_$t" -max_total_time="$seconds" -timeout=1 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" "${extra_flags[@]}" \
    "${dict[@]}" "$corpus" "$build_dir/seeds/$t" "${extra[@]}" >"$log" 2>&1 || status=failed
  elapsed=$(($(date +%s) - start))
  crashes=$(find "$findings" -type f -name 'crash-*' | wc -l)
  timeouts=$(find "$findings" -type f -name 'timeout-*' | wc -l)
  ooms=$(find "$findings" -type f -name 'oom-*' | wc -l)
  leaks=$(find "$findings" -type f -name 'leak-*' | wc -l)
  if [ -n "$(ls -A "$findings")" ]; then status=found; else rmdir "$findings"; fi
  [ "$status" != ok ] && found=1
  printf '%-16s %6s %12s %8s %6s %7s %6s %7s %8s %5s %5s %s\n' "$t" "$elapsed" \
    "$(last_value "$log" 'stat::number_of_executed_units:')" \
    "$(last_value "$log" 'stat::average_exec_per_sec:')" \
    "$(last_value "$log" 'cov:')" "$(last_value "$log" 'ft:')" \
    "$(find "$corpus" -type f | wc -l)" "$crashes" "$timeouts" "$ooms" "$leaks" "$status" \
    >>"$summary"
done
echo
cat "$summary"
echo "(findings so far in $build_dir/findings; corpora in $build_dir/corpus)"
exit "$found"
