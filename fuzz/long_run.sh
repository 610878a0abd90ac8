#!/usr/bin/env bash
# The long fuzzing run (not CI; CI runs fuzz/run.sh for 20 s a target): every libFuzzer target to
# at least FUZZ_TOTAL executions (default 10,000,000), split over FUZZ_JOBS processes (default: the
# machine's processors), keeping the grown corpus in <build>/corpus/<target> so that a later run
# goes on from it. Fails as fuzz/run.sh does, on the first crash, leak, undefined behaviour, hang
# or out-of-memory, leaving the input in <build>/artifacts/<target>/.
# At the rates of a 2-core machine (formula_fuzz ~1,700, request_fuzz ~750 executions a second
# per process) 10 million executions take about 1.6 and 3.7 hours of one processor.
# Usage: bash fuzz/long_run.sh [build-dir] [target...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
total="${FUZZ_TOTAL:-10000000}"
jobs="${FUZZ_JOBS:-$(nproc)}"
export FUZZ_JOBS="$jobs"
export FUZZ_RUNS=$(((total + jobs - 1) / jobs))
export FUZZ_KEEP_CORPUS=1
exec bash "$root/fuzz/run.sh" "$@"
