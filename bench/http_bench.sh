#!/usr/bin/env bash
# HTTP benchmark on loopback (wrk): footpoint-server against an echo baseline.
#   bench/http_bench.sh [BUILD_DIR]          (a Release build: BUILD_DIR/footpoint-server and
#                                              BUILD_DIR/bench/echo_server_bench; default build)
# Environment: DURATION (seconds per wrk run, default 10), HALF_WIDTHS (domains, default "3 25"),
# REPEATS (batch pairs per domain, default 3), PORT (default 18471; the echo uses PORT+1),
# CONNECTIONS (single-point runs, default 50), BATCH_CONNECTIONS (default 4).
# Runs:
#   1. single-point POST /v1/geometries/{id}/project on the [GSA] Example 1 surface, random
#      points, CONNECTIONS connections: requests/s and p50/p99 latency; the same against the echo
#      server (same HTTP layer and JSON reader/writer, no projection);
#   2. 10,000-point batches on the same surface and on the echo server, in REPEATS back-to-back
#      pairs per domain: the ratio of each pair, and the medians (a pair sees the same machine
#      load, so the ratio moves less than either throughput). The echo replays the server's own
#      answer to the batch (echo_server_bench --replay): the same request parsed, the same
#      response written, byte for byte, without the projection;
#   3. on the first domain, the same batches with "fields": ["foot_point", "distance"] against
#      the full answer, in REPEATS interleaved pairs: what trimming the answer saves.
# Only 127.0.0.1 is targeted; every step is bounded by `timeout` and the whole script by 600 s.
set -euo pipefail

if [ -z "${FOOTPOINT_HTTP_BENCH_BOUNDED:-}" ]; then
  export FOOTPOINT_HTTP_BENCH_BOUNDED=1
  exec timeout --kill-after=10 600 "$0" "$@"
fi

BUILD=${1:-build}
DURATION=${DURATION:-10}
PORT=${PORT:-18471}
ECHO_PORT=$((PORT + 1))
CONNECTIONS=${CONNECTIONS:-50}
BATCH_CONNECTIONS=${BATCH_CONNECTIONS:-4}
HOST=127.0.0.1
SERVER="$BUILD/footpoint-server"
ECHO="$BUILD/bench/echo_server_bench"
for tool in wrk curl; do command -v "$tool" >/dev/null || { echo "http_bench: $tool is required" >&2; exit 2; }; done
for exe in "$SERVER" "$ECHO"; do [ -x "$exe" ] || { echo "http_bench: $exe not built" >&2; exit 2; }; done

work=$(mktemp -d)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

start() {  # start EXE PORT [ARGS...]: runs it on 127.0.0.1:PORT with default settings, waits for /healthz
  "$1" --host "$HOST" --port "$2" "${@:3}" >/dev/null 2>&1 &  # the request log (one line each) is discarded
  pids+=($!)
  for _ in $(seq 100); do
    curl -fsS --max-time 1 "http://$HOST:$2/healthz" >/dev/null 2>&1 && return 0
    sleep 0.1
  done
  echo "http_bench: $1 did not start:" >&2
  timeout 2 "$1" --host "$HOST" --port "$2" "${@:3}" >&2 || true
  exit 1
}

# Random points around the surface's strip; single.lua draws a new point per request.
cat >"$work/single.lua" <<'LUA'
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
math.randomseed(7)
request = function()
  local body = string.format('{"point":[%.17g,%.17g,%.17g]}',
    math.random() * 40 - 20, math.random() * 6 - 3, math.random() * 3 - 1.5)
  return wrk.format(nil, nil, nil, body)
end
LUA
# The batch body (10,000 points, the same distribution) is a file: wrk posts it, and the echo
# replays the server's answer to it.
awk 'BEGIN {
  srand(11)
  printf "{\"points\":["
  for (i = 0; i < 10000; ++i)
    printf "%s[%.17g,%.17g,%.17g]", (i ? "," : ""), rand() * 40 - 20, rand() * 6 - 3, rand() * 3 - 1.5
  printf "]}"
}' >"$work/batch.json"
sed 's/]}$/],"fields":["foot_point","distance"]}/' "$work/batch.json" >"$work/batch_fields.json"
for name in batch batch_fields; do
  cat >"$work/$name.lua" <<LUA
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
local f = assert(io.open("$work/$name.json", "rb"))
wrk.body = f:read("*a")
f:close()
LUA
done

# HALF_WIDTHS: the parameter domains [-w,w]^2 measured (default "3 25"): 3 is S1 of the Open CASCADE
# comparison (bench/occt/), 25 the reference cases' domain for this example, where the surface
# covers itself ~16 times (each 3-D point has ~8 parameter preimages) and a global answer needs
# ~29 local solves per near point.
read -r -a widths <<<"${HALF_WIDTHS:-${HALF_WIDTH:-3 25}}"

run_wrk() {  # run_wrk NAME CONNECTIONS SCRIPT URL -> wrk output in $work/NAME.txt
  timeout $((DURATION + 30)) wrk -t2 -c"$2" -d"${DURATION}s" --timeout 30s --latency -s "$3" "$4" >"$work/$1.txt"
}
rps() { awk '/^Requests\/sec:/ {print $2}' "$work/$1.txt"; }
pct() { awk -v p="$2" '$1 == p {print $2}' "$work/$1.txt"; }
errors() { awk '/Non-2xx|Socket errors/ {print}' "$work/$1.txt"; }
points() { awk -v r="$(rps "$1")" 'BEGIN {printf "%.0f", r * 10000}'; }

REPEATS=${REPEATS:-3}
median() { sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

# The echo answers a batch with the server's own results for it (--replay), so that both write
# the same bytes: the server is asked once per domain first.
start "$SERVER" "$PORT"
ids=()
replays=()
for w in "${widths[@]}"; do
  surface='{"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-'"$w"','"$w"'],"v":[-'"$w"','"$w"']}}'
  id=$(curl -fsS --max-time 30 -H 'Content-Type: application/json' -d "$surface" "http://$HOST:$PORT/v1/geometries" |
    sed -E 's/.*"geometry_id":"([0-9a-f]+)".*/\1/')
  ids+=("$id")
  curl -fsS --max-time 60 -H 'Content-Type: application/json' --data-binary "@$work/batch.json" \
    "http://$HOST:$PORT/v1/geometries/$id/project" >"$work/replay_$id.json"
  replays+=(--replay "$id=$work/replay_$id.json")
done
start "$ECHO" "$ECHO_PORT" "${replays[@]}"
for k in "${!widths[@]}"; do
  w=${widths[$k]}
  id=${ids[$k]}
  url="http://$HOST:$PORT/v1/geometries/$id/project"
  echo_url="http://$HOST:$ECHO_PORT/v1/geometries/$id/project"
  timeout 30 wrk -t2 -c"$CONNECTIONS" -d2s -s "$work/single.lua" "$url" >/dev/null  # warm-up
  run_wrk "single_$w" "$CONNECTIONS" "$work/single.lua" "$url"
  for r in $(seq "$REPEATS"); do
    run_wrk "batch_${w}_$r" "$BATCH_CONNECTIONS" "$work/batch.lua" "$url"
    run_wrk "echo_batch_${w}_$r" "$BATCH_CONNECTIONS" "$work/batch.lua" "$echo_url"
  done
done
timeout 30 wrk -t2 -c"$CONNECTIONS" -d2s -s "$work/single.lua" "$echo_url" >/dev/null
run_wrk echo_single "$CONNECTIONS" "$work/single.lua" "$echo_url"
fields_url="http://$HOST:$PORT/v1/geometries/${ids[0]}/project"
for r in $(seq "$REPEATS"); do
  run_wrk "full_$r" "$BATCH_CONNECTIONS" "$work/batch.lua" "$fields_url"
  run_wrk "fields_$r" "$BATCH_CONNECTIONS" "$work/batch_fields.lua" "$fields_url"
done

echo "http_bench: wrk -t2 on $HOST, ${DURATION}s per run, $(nproc) cores; [GSA] Example 1 surface"
printf '  echo baseline: single point, %d connections: %s req/s (p50 %s, p99 %s)\n' \
  "$CONNECTIONS" "$(rps echo_single)" "$(pct echo_single 50%)" "$(pct echo_single 99%)"
for w in "${widths[@]}"; do
  printf '  domain [-%s,%s]^2: single point, %d connections: %s req/s (p50 %s, p99 %s)\n' \
    "$w" "$w" "$CONNECTIONS" "$(rps "single_$w")" "$(pct "single_$w" 50%)" "$(pct "single_$w" 99%)"
  ratios=()
  for r in $(seq "$REPEATS"); do
    ratio=$(awk -v a="$(rps "batch_${w}_$r")" -v b="$(rps "echo_batch_${w}_$r")" 'BEGIN {if (b > 0) printf "%.1f", 100 * a / b; else print "nan"}')
    ratios+=("$ratio")
    printf '    pair %d, 10,000-point batches, %d connections: %s points/s (p50 %s), echo %s points/s: %s%%\n' \
      "$r" "$BATCH_CONNECTIONS" "$(points "batch_${w}_$r")" "$(pct "batch_${w}_$r" 50%)" "$(points "echo_batch_${w}_$r")" "$ratio"
  done
  printf '    medians on [-%s,%s]^2: %s points/s, echo %s points/s; batch throughput / echo throughput: %s%% (target >= 50%%)\n' \
    "$w" "$w" \
    "$(for r in $(seq "$REPEATS"); do points "batch_${w}_$r"; echo; done | median)" \
    "$(for r in $(seq "$REPEATS"); do points "echo_batch_${w}_$r"; echo; done | median)" \
    "$(printf '%s\n' "${ratios[@]}" | median)"
done
full_bytes=$(curl -fsS --max-time 60 -H 'Content-Type: application/json' --data-binary "@$work/batch.json" "$fields_url" | wc -c)
fields_bytes=$(curl -fsS --max-time 60 -H 'Content-Type: application/json' --data-binary "@$work/batch_fields.json" "$fields_url" | wc -c)
printf '  fields ["foot_point","distance"] on [-%s,%s]^2, 10,000-point batches: %s bytes an answer instead of %s\n' \
  "${widths[0]}" "${widths[0]}" "$fields_bytes" "$full_bytes"
speedups=()
for r in $(seq "$REPEATS"); do
  speedup=$(awk -v a="$(rps "fields_$r")" -v b="$(rps "full_$r")" 'BEGIN {if (b > 0) printf "%.3f", a / b; else print "nan"}')
  speedups+=("$speedup")
  printf '    pair %d: full %s points/s (p50 %s), fields %s points/s (p50 %s): %sx\n' "$r" \
    "$(points "full_$r")" "$(pct "full_$r" 50%)" "$(points "fields_$r")" "$(pct "fields_$r" 50%)" "$speedup"
done
printf '    medians: full %s points/s, fields %s points/s; fields / full throughput: %sx\n' \
  "$(for r in $(seq "$REPEATS"); do points "full_$r"; echo; done | median)" \
  "$(for r in $(seq "$REPEATS"); do points "fields_$r"; echo; done | median)" \
  "$(printf '%s\n' "${speedups[@]}" | median)"
runs=(echo_single)
for w in "${widths[@]}"; do
  runs+=("single_$w")
  for r in $(seq "$REPEATS"); do runs+=("batch_${w}_$r" "echo_batch_${w}_$r"); done
done
for r in $(seq "$REPEATS"); do runs+=("full_$r" "fields_$r"); done
for run in "${runs[@]}"; do
  e=$(errors "$run")
  [ -z "$e" ] || echo "  $run: $e"
done
