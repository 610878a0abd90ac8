#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer + UndefinedBehaviorSanitizer (the top-level
# FOOTPOINT_SANITIZE option, -O1 -g1: ASan's usual level, line tables for the reports) and runs it
# with ctest, one suite per core (the timed ones alone). Any sanitizer report fails
# the run: UB does not recover (-fno-sanitize-recover), ASan aborts, leaks are checked at exit.
# The compiler is Debian's clang 14 (the fuzz targets' compiler): it builds the instrumented suite
# in about half GCC 12's time, and the second compiler sees the code the Release build (GCC,
# scripts/test.sh, held to -Werror) does not. Warnings are not errors here.
# The deploy_* tests are left out: they check the Release image's layout and manifests (an
# instrumented binary links the sanitizer runtimes, which the runtime image rightly lacks); so are
# the reference_generator_* tests: Python recomputing the reference data, no instrumented code runs
# (the Release suite runs them), and projection_dump_reads_references: it checks that a tool reads
# every reference file, and the suites run the same code instrumented. So is footpoint-import
# (tools/step_import/): glue over Open CASCADE's uninstrumented STEP reader, tested in the Release
# suite.
# Usage: bash scripts/sanitize.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test clang-14 libclang-rt-14-dev
build="${1:-build-asan}"
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DFOOTPOINT_SANITIZE=ON -DFOOTPOINT_WERROR=OFF -DFOOTPOINT_BUILD_BENCH=OFF \
  -DFOOTPOINT_BUILD_IMPORT=OFF
cmake --build "$build" -j"$(nproc)"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
ctest --test-dir "$build" --output-on-failure --timeout 1800 --exclude-regex '^(deploy_|reference_generator_|projection_dump_)' --no-tests=error \
  -j"$(nproc)"
