#!/usr/bin/env bash
# The shared geometry registry's costs, on loopback, against a redis-server of its own:
#   bench/registry_bench.sh [BUILD_DIR]        (a Release build: BUILD_DIR/footpoint-server)
# Environment: ROUNDS (interleaved pairs, default 5), DURATION (seconds per wrk run, default 3),
# CONNECTIONS (default 16), GEOMETRIES (level-2 samples, default 15), PORT (default 18491; the
# script uses PORT..PORT+3).
#   1. level-1 hits: single-point POST /v1/geometries/{id}/project with the registry off and on
#      (two servers, same binary, same settings), wrk runs alternating off/on, ROUNDS pairs: the
#      median of the on/off throughput ratios (goal >= 0.97);
#   2. a level-2 hit (the first request for an id on the replica that did not see the post: Redis
#      GETEX + hash check + parse + compile + the point) against a cold compile (POST
#      /v1/project with a new definition inline, registry off) and a level-1 hit, medians over
#      GEOMETRIES geometries of curl's time_total; and the Redis read alone (the registry's
#      command histogram);
#   3. Redis killed: level-1 hit throughput (ratio to off), and the medians of an id in neither
#      level (503 registry_unavailable) and of a POST (answered not_stored) against a POST while
#      Redis was up.
# Only 127.0.0.1 is used; the whole script is bounded by 600 s.
set -euo pipefail

if [ -z "${FOOTPOINT_REGISTRY_BENCH_BOUNDED:-}" ]; then
  export FOOTPOINT_REGISTRY_BENCH_BOUNDED=1
  exec timeout --kill-after=10 600 "$0" "$@"
fi

BUILD=${1:-build}
ROUNDS=${ROUNDS:-5}
DURATION=${DURATION:-3}
CONNECTIONS=${CONNECTIONS:-16}
GEOMETRIES=${GEOMETRIES:-15}
PORT=${PORT:-18491}
HOST=127.0.0.1
OFF=$PORT ON=$((PORT + 1)) OTHER=$((PORT + 2)) REDIS_PORT=$((PORT + 3))
SERVER="$BUILD/footpoint-server"
for tool in wrk curl jq redis-server redis-cli; do
  command -v "$tool" >/dev/null || { echo "registry_bench: $tool is required" >&2; exit 2; }
done
[ -x "$SERVER" ] || { echo "registry_bench: $SERVER not built" >&2; exit 2; }

work=$(mktemp -d)
pids=()
redis_pid=
cleanup() {
  for pid in "${pids[@]}" $redis_pid; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}" $redis_pid; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

export REDISCLI_AUTH="bench-$RANDOM-$RANDOM"
start_redis() {
  redis-server --port "$REDIS_PORT" --bind "$HOST" --save '' --appendonly no --dir "$work" \
    --requirepass "$REDISCLI_AUTH" >"$work/redis.log" 2>&1 &
  redis_pid=$!
  for _ in $(seq 100); do redis-cli -p "$REDIS_PORT" ping 2>/dev/null | grep -q PONG && return 0; sleep 0.05; done
  echo "registry_bench: redis-server did not start" >&2
  exit 1
}
start() {  # start PORT [ENV...]: a footpoint-server on 127.0.0.1:PORT, one numerical thread
  env "${@:2}" "$SERVER" --host "$HOST" --port "$1" --threads 1 --connection-threads 64 --log-level warn \
    >"$work/server-$1.log" 2>&1 &
  pids+=($!)
  for _ in $(seq 100); do curl -fsS --max-time 1 "http://$HOST:$1/healthz" >/dev/null 2>&1 && return 0; sleep 0.1; done
  echo "registry_bench: the server on port $1 did not start" >&2
  exit 1
}
registry=(FOOTPOINT_REGISTRY_URL="redis://$HOST:$REDIS_PORT/0" FOOTPOINT_REGISTRY_PASSWORD="$REDISCLI_AUTH")
start_redis
start "$OFF"
start "$ON" "${registry[@]}"
start "$OTHER" "${registry[@]}"

post() { curl -fsS "http://$HOST:$1$2" -H 'Content-Type: application/json' -d "$3"; }
seconds() { curl -s -o /dev/null -w '%{time_total}\n' "http://$HOST:$1$2" -H 'Content-Type: application/json' -d "$3"; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
surface() { printf '{"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)+%s","domain":{"u":[-3,3],"v":[-3,3]}}' "$1"; }

# ---- 1. level-1 hits, registry off and on ------------------------------------------------------
id=$(post "$OFF" /v1/geometries "$(surface 0)" | jq -r .geometry_id)
post "$ON" /v1/geometries "$(surface 0)" >/dev/null
cat >"$work/single.lua" <<'LUA'
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
wrk.body = '{"point":[1,2,2]}'
LUA
rps() {  # rps PORT: requests/s of one wrk run
  wrk -t1 -c"$CONNECTIONS" -d"${DURATION}s" -s "$work/single.lua" "http://$HOST:$1/v1/geometries/$id/project" |
    awk '/^Requests\/sec:/ { print $2 }'
}
rps "$OFF" >/dev/null  # warm-up
rps "$ON" >/dev/null
ratios=()
echo "1. level-1 hit throughput, single point, $CONNECTIONS connections, ${DURATION} s runs, off/on alternating:"
for round in $(seq "$ROUNDS"); do
  off=$(rps "$OFF")
  on=$(rps "$ON")
  ratio=$(awk -v a="$on" -v b="$off" 'BEGIN { printf "%.4f", a / b }')
  ratios+=("$ratio")
  echo "   round $round: off $off/s, on $on/s, on/off $ratio"
done
echo "   median on/off: $(printf '%s\n' "${ratios[@]}" | median) (goal >= 0.97)"

# ---- 2. a level-2 hit against a cold compile -----------------------------------------------------
: >"$work/l2" && : >"$work/l1" && : >"$work/cold"
for k in $(seq "$GEOMETRIES"); do
  gid=$(post "$ON" /v1/geometries "$(surface "$k")" | jq -r .geometry_id)
  seconds "$OTHER" "/v1/geometries/$gid/project" '{"point":[1,2,2]}' >>"$work/l2"
  seconds "$OTHER" "/v1/geometries/$gid/project" '{"point":[1,2,2]}' >>"$work/l1"
  seconds "$OFF" /v1/project "{\"geometry\":$(surface "$((k + 1000))"),\"point\":[1,2,2]}" >>"$work/cold"
done
metrics=$(curl -fsS "http://$HOST:$OTHER/metrics")
get_mean=$(awk '/^footpoint_registry_command_duration_seconds_sum\{command="get"\}/ { s = $2 }
  /^footpoint_registry_command_duration_seconds_count\{command="get"\}/ { n = $2 }
  END { printf "%.3f", n ? s / n * 1e3 : 0 }' <<<"$metrics")
ms() { median | awk '{ printf "%.2f ms", $1 * 1e3 }'; }
echo "2. one point, medians over $GEOMETRIES geometries (curl time_total, loopback):"
echo "   level-2 hit (GETEX + hash check + parse + compile): $(ms <"$work/l2")"
echo "   cold compile (definition inline, registry off):     $(ms <"$work/cold")"
echo "   level-1 hit:                                        $(ms <"$work/l1")"
echo "   of which the Redis read (mean of the registry's get histogram): $get_mean ms"

# ---- 3. Redis killed -------------------------------------------------------------------------------
: >"$work/post_up" && : >"$work/post_down" && : >"$work/unknown"
for k in $(seq 10); do seconds "$ON" /v1/geometries "$(surface "$((k + 2000))")" >>"$work/post_up"; done
kill -KILL "$redis_pid"
wait "$redis_pid" 2>/dev/null || true
redis_pid=
sleep 0.5
off=$(rps "$OFF")
on=$(rps "$ON")
for k in $(seq 10); do
  seconds "$ON" /v1/geometries "$(surface "$((k + 3000))")" >>"$work/post_down"
  seconds "$ON" "/v1/geometries/$(printf '%032x' "$k")/project" '{"point":[1,2,2]}' >>"$work/unknown"
done
echo "3. Redis killed:"
echo "   level-1 hits: off $off/s, on $on/s, on/off $(awk -v a="$on" -v b="$off" 'BEGIN { printf "%.4f", a / b }')"
echo "   an id in neither level (503 registry_unavailable): $(ms <"$work/unknown")"
echo "   POST /v1/geometries, compiled and not stored: $(ms <"$work/post_down") (stored, Redis up: $(ms <"$work/post_up"))"
