#!/usr/bin/env bash
# Installs the dependencies of the service and of the tests (scripts/install-deps.sh --test),
# builds everything (Release, -O3) and runs the whole test suite with ctest, one suite per core (the
# timed ones alone: tests/CMakeLists.txt); a build without tests fails. In CI (CI=true) warnings are errors. Usage: bash scripts/test.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --test
build="${1:-build}"
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DFOOTPOINT_WERROR="$werror"
cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure --timeout 900 --no-tests=error -j"$(nproc)"
