#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, see fuzz/CMakeLists.txt) and runs each for a
# bounded time, starting from its seed corpus in fuzz/corpus/<target>/. Fails on any crash, leak,
# undefined behaviour, timeout or out-of-memory: libFuzzer exits non-zero and leaves the input as
# <build>/artifacts/<target>/crash-* (or leak-*, timeout-*, oom-*); rerun it with
#   <build>/<target> <that file>
# Usage: bash fuzz/run.sh [build-dir] [target...]
#   FUZZ_SECONDS  seconds per target (default 60)
#   FUZZ_JOBS     parallel fuzzing processes per target (default 1)
#   FUZZ_TIMEOUT  seconds one input may run before it counts as a hang (default 60: the request
#                 target's deadline is 2 s, but compiling a geometry is not bounded by it and
#                 runs ~20 times slower instrumented: 1 s in Release is 25 s here)
#   FUZZ_RUNS     executions per fuzzing process instead of a time bound (FUZZ_SECONDS is then
#                 ignored); fuzz/long_run.sh sets it
#   FUZZ_KEEP_CORPUS=1  grow the corpus in <build>/corpus/<target> from run to run instead of
#                 starting from the seeds each time
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/fuzz/install.sh"

build="$(realpath -m "${1:-$root/build-fuzz}")"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(formula_fuzz request_fuzz); fi
seconds="${FUZZ_SECONDS:-60}"
runs="${FUZZ_RUNS:-}"
keep="${FUZZ_KEEP_CORPUS:-0}"
jobs="${FUZZ_JOBS:-1}"
timeout_s="${FUZZ_TIMEOUT:-60}"

# The top-level project with clang, -O1 (libFuzzer's usual level: fast, still precise reports),
# no tests or benchmarks; fuzz/fuzz_build.cmake adds the instrumentation and the targets.
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" -DFOOTPOINT_BUILD_TESTS=OFF -DFOOTPOINT_BUILD_BENCH=OFF \
  -DCMAKE_PROJECT_footpoint_INCLUDE="$root/fuzz/fuzz_build.cmake" >/dev/null
cmake --build "$build" --target "${targets[@]}" -j"$(nproc)"

# Sanitizer settings: a report is fatal, leaks are checked at exit of every input's process.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

status=0
for target in "${targets[@]}"; do
  name="${target%_fuzz}"
  seeds="$root/fuzz/corpus/$name"
  # The corpus the run grows is in the build dir, new each run (a grown corpus would spend the
  # time budget replaying its slow inputs); the repo keeps only the small seed corpus.
  work="$build/corpus/$name"
  if [ "$keep" != 1 ]; then rm -rf "$work"; fi
  artifacts="$build/artifacts/$target"  # this run's findings only
  rm -rf "$artifacts"
  mkdir -p "$work" "$artifacts"
  log="$build/$target.log"
  bound="${seconds}s"
  if [ -n "$runs" ]; then bound="$runs executions x $jobs process(es)"; fi
  echo "== $target: $bound from $(find "$seeds" -type f | wc -l) seeds and $(find "$work" -type f | wc -l) kept inputs (log: $log)"
  # -timeout: one input running longer than this is a hang.
  # -rss_limit_mb: a runaway allocation is a failure, not a slow machine.
  # -max_len: formulas long enough to reach the 20,000-node limit (the 19,999-character one is
  # muparser's, checked by the unit tests).
  args=(-timeout="$timeout_s" -rss_limit_mb=2048 -max_len=16384 -artifact_prefix="$artifacts/"
        -print_final_stats=1)
  if [ -n "$runs" ]; then args+=(-runs="$runs"); else args+=(-max_total_time="$seconds"); fi
  # Several processes write their logs as fuzz-<n>.log in the working directory.
  if [ "$jobs" -gt 1 ]; then args+=(-jobs="$jobs" -workers="$jobs"); fi
  # (with several processes the parent may exit 0 when one of them failed: an artifact fails too)
  if (cd "$build" && "$build/$target" "${args[@]}" "$work" "$seeds" >"$log" 2>&1) &&
    [ -z "$(ls -A "$artifacts")" ]; then
    grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|Done [0-9]+ runs" "$log" | sed 's/^/   /' || true
    # with several processes, each writes its own log and final stats
    if [ "$jobs" -gt 1 ]; then
      total=$(cat "$build"/fuzz-*.log 2>/dev/null | awk '/^stat::number_of_executed_units/ {n += $2} END {print n + 0}')
      echo "   executions over the $jobs processes: $total"
    fi
  else
    status=1
    echo "!! $target FAILED; last lines of $log:"
    tail -n 40 "$log"
    ls -l "$artifacts"
  fi
done
exit $status
