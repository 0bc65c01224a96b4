#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, the `fuzz` preset: clang, ASan+UBSan) and runs each
# for a bounded time from its seed corpus (tests/fuzz/corpus/<target>). Fails on the first crash,
# leak, timeout or sanitizer report; the input that caused it is left in build/fuzz/artifacts/.
#
#   scripts/fuzz.sh                      # every target, FUZZ_SECONDS (default 25) each: CI
#   FUZZ_SECONDS=0 FUZZ_RUNS=10000000 scripts/fuzz.sh plan goal   # 10 million runs of two
#   FUZZ_TIMEOUT=120 chrt -i 0 scripts/fuzz.sh ...                 # beside other work
#
# New inputs the fuzzer finds go to build/fuzz/corpus/<target>, not into the repository: copy
# one into tests/fuzz/corpus/<target>/ when it is worth keeping (a regression, a new shape).
set -euo pipefail
cd "$(dirname "$0")/.."

all=(map_movingai map_ros vehicle_state map_update plan goal planner_status vehicle_description)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${all[@]}")
seconds=${FUZZ_SECONDS:-25}
runs=${FUZZ_RUNS:--1}
# Seconds one input may take before it counts as a hang; raise it for a long run at idle priority.
unit_timeout=${FUZZ_TIMEOUT:-10}

cmake --preset fuzz >/dev/null
cmake --build build/fuzz -j"${FUZZ_BUILD_JOBS:-2}" --target grip_fuzz

# Inputs larger than this add little and slow every run (a map file's header and a few rows,
# a plan of a few dozen steps, a stream of map updates).
declare -A max_len=([map_movingai]=4096 [map_ros]=4096 [map_update]=8192 [plan]=4096)
mkdir -p build/fuzz/artifacts
failed=()
for t in "${targets[@]}"; do
  exe=build/fuzz/bin/fuzz_$t
  [ -x "$exe" ] || { echo "fuzz: no target '$t' (have: ${all[*]})" >&2; exit 2; }
  work=build/fuzz/corpus/$t
  mkdir -p "$work"
  echo "fuzz: $t (${seconds}s, runs ${runs})"
  # The allocator keeps freed memory instead of returning it to the kernel after each input: a
  # target that allocates large blocks otherwise spends most of its time in page faults.
  if ! ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_release_to_os_interval_ms=-1 \
      UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
      "$exe" -max_total_time="$seconds" -runs="$runs" -max_len="${max_len[$t]:-2048}" \
      -timeout="$unit_timeout" -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="build/fuzz/artifacts/$t-" "$work" "tests/fuzz/corpus/$t" \
      >"build/fuzz/$t.log" 2>&1; then
    failed+=("$t")
    tail -n 60 "build/fuzz/$t.log" >&2
  fi
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "build/fuzz/$t.log" | sed "s/^/fuzz: $t /"
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]} (inputs in build/fuzz/artifacts/)" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} target(s) clean"
