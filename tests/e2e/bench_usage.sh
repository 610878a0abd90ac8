#!/usr/bin/env bash
# The bench programs (build/bench/*_bench): --help prints their usage and exits 0; a count that is
# no positive integer or an argument they do not take exits 2 with the usage on stderr, instead of
# a run over 0 points (rows of NaN). Usage: tests/e2e/bench_usage.sh BUILD/bench
set -u
dir=$1
failed=0
fail() { echo "FAIL: $*"; failed=1; }
for bench in surface_bench json_bench closure_bench formula_bench curve_bench grain_bench; do
  out=$("$dir/$bench" --help 2>&1); code=$?
  [ "$code" -eq 0 ] || fail "$bench --help exits $code"
  case $out in "usage: $bench"*) ;; *) fail "$bench --help prints: $out" ;; esac
  case $out in *nan*|*NaN*) fail "$bench --help prints NaN" ;; esac
done
for args in "surface_bench abc" "surface_bench 0" "surface_bench 10 -3" "surface_bench --reps x --peer" \
            "surface_bench --sections 9" "surface_bench --bogus" "json_bench 12x" "json_bench 0" \
            "closure_bench 5" "formula_bench --fast" "curve_bench 100" "grain_bench 0" "grain_bench 3 x" \
            "grain_bench 1 2 3"; do
  read -r bench rest <<<"$args"
  # shellcheck disable=SC2086 # the arguments split as written
  err=$("$dir/$bench" $rest 2>&1 >/dev/null); code=$?
  [ "$code" -eq 2 ] || fail "$args exits $code"
  case $err in *"usage: $bench"*) ;; *) fail "$args prints no usage: $err" ;; esac
done
exit $failed
