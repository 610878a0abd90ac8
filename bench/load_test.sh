#!/usr/bin/env bash
# Bounded load and shutdown test on loopback (127.0.0.1 only), against a Release footpoint-server.
#   bench/load_test.sh [BUILD_DIR]      (BUILD_DIR/footpoint-server; default build)
# Environment: DURATION (seconds of load, default 60), CONNECTIONS (default 32), PORT (default
# 18491), SHUTDOWN_BATCH (points in each in-flight request at SIGTERM, default 100000).
#
# 1. Load: wrk at saturation for DURATION seconds with a mix of requests (lua below): single
#    points and batches of 100 on a cached surface, batches of 1,000 on a cached spatial curve,
#    inline /v1/project on a few geometries (cache lookups), and 10% bad requests (malformed JSON,
#    unknown method, wrong dimension, unknown id). Pass: no 5xx, no socket errors, the server
#    alive and still giving the same answer, RSS flat after warm-up (the last sample at most 10%
#    + 16 MiB above the sample at the end of the first sixth). RSS is read from /proc/PID/status
#    every second.
# 2. Shutdown: load again, three large batches in flight, then SIGTERM. Pass: the in-flight
#    batches complete (200, every point answered), a new connection is refused, the process exits
#    0. wrk's connections still open at the signal get 503 shutting_down or are closed: counted.
# Exit status 0 when every check passed. Every step is bounded by `timeout`.
set -euo pipefail

if [ -z "${FOOTPOINT_LOAD_TEST_BOUNDED:-}" ]; then
  export FOOTPOINT_LOAD_TEST_BOUNDED=1
  exec timeout --kill-after=10 $(( ${DURATION:-60} + 300 )) "$0" "$@"
fi

BUILD=${1:-build}
DURATION=${DURATION:-60}
CONNECTIONS=${CONNECTIONS:-32}
PORT=${PORT:-18491}
SHUTDOWN_BATCH=${SHUTDOWN_BATCH:-100000}
HOST=127.0.0.1
URL="http://$HOST:$PORT"
SERVER="$BUILD/footpoint-server"
for tool in wrk curl python3; do command -v "$tool" >/dev/null || { echo "load_test: $tool is required" >&2; exit 2; }; done
[ -x "$SERVER" ] || { echo "load_test: $SERVER not built" >&2; exit 2; }

work=$(mktemp -d)
server_pid=""
sampler_pid=""
cleanup() {
  if [ -n "$sampler_pid" ]; then kill "$sampler_pid" 2>/dev/null || true; fi
  if [ -n "$server_pid" ]; then kill -KILL "$server_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 143' TERM INT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$SERVER" --host "$HOST" --port "$PORT" --log-level warn >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do
  curl -fsS --max-time 1 "$URL/healthz" >/dev/null 2>&1 && break
  sleep 0.1
done
curl -fsS --max-time 1 "$URL/healthz" >/dev/null || { cat "$work/server.log"; echo "load_test: server did not start" >&2; exit 1; }

surface='{"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}}'
curve='{"type":"implicit_curve","equations":["x^2/9+y^2/16+z^2/9-1","x^2+y^2-4*z"],"domain":{"x":[-300,300],"y":[-300,300],"z":[-300,300]}}'
post() { curl -sS --max-time 60 -H 'Content-Type: application/json' --data-binary "$2" "$URL$1"; }
surface_id=$(post /v1/geometries "$surface" | python3 -c 'import json,sys; print(json.load(sys.stdin)["geometry_id"])')
curve_id=$(post /v1/geometries "$curve" | python3 -c 'import json,sys; print(json.load(sys.stdin)["geometry_id"])')
reference=$(post "/v1/geometries/$surface_id/project" '{"point":[1,2,2]}' | python3 -c 'import json,sys; print(json.load(sys.stdin)["result"]["distance"])')

# The request mix. Each wrk thread counts responses by status; done() adds them up.
cat >"$work/mix.lua" <<LUA
local surface_id, curve_id = "$surface_id", "$curve_id"
local threads = {}
function setup(thread) table.insert(threads, thread) end

local function point(scale)
  return string.format('[%.17g,%.17g,%.17g]', (math.random() * 2 - 1) * scale,
    (math.random() * 2 - 1) * scale, (math.random() * 2 - 1) * scale)
end
local function batch(n, scale)
  local parts = {}
  for i = 1, n do parts[i] = point(scale) end
  return '{"points":[' .. table.concat(parts, ',') .. ']}'
end
local inline = {
  '{"type":"parametric_surface","x":"u","y":"v","z":"u*u-v*v","domain":{"u":[-2,2],"v":[-2,2]}}',
  '{"type":"parametric_curve","x":"cos(t)","y":"2*sin(t)","z":"t/5","domain":{"t":[0,12]}}',
  '{"type":"implicit_curve","equations":["x^2+y^2/4-1"],"domain":{"x":[-3,3],"y":[-3,3]}}',
}
local bad = {
  {"/v1/geometries/" .. surface_id .. "/project", '{"point":[1,2,'},
  {"/v1/geometries/" .. surface_id .. "/project", '{"point":[1,2,2],"method":"magic"}'},
  {"/v1/geometries/" .. surface_id .. "/project", '{"point":[1,2]}'},
  {"/v1/geometries/0123456789abcdef0123456789abcdef/project", '{"point":[1,2,2]}'},
  {"/v1/project", '{"point":[1,2,2],"geometry":{"type":"torus"}}'},
}
local batches100, batches1000 = {}, {}

function init(args)
  math.randomseed(os.time() + math.floor(os.clock() * 1e6))
  counts = {}
  for i = 1, 8 do batches100[i] = batch(100, 20) end
  for i = 1, 4 do batches1000[i] = batch(1000, 6) end
end

function request()
  local r = math.random()
  local headers = {["Content-Type"] = "application/json"}
  if r < 0.55 then
    return wrk.format("POST", "/v1/geometries/" .. surface_id .. "/project", headers, '{"point":' .. point(20) .. '}')
  elseif r < 0.70 then
    return wrk.format("POST", "/v1/geometries/" .. surface_id .. "/project", headers, batches100[math.random(#batches100)])
  elseif r < 0.75 then
    return wrk.format("POST", "/v1/geometries/" .. curve_id .. "/project", headers, batches1000[math.random(#batches1000)])
  elseif r < 0.90 then
    local g = math.random(#inline)
    local p = g == 1 and point(2) or (g == 2 and point(3) or string.format('[%.17g,%.17g]', math.random() * 4 - 2, math.random() * 4 - 2))
    return wrk.format("POST", "/v1/project", headers, '{"geometry":' .. inline[g] .. ',"point":' .. p .. '}')
  else
    local b = bad[math.random(#bad)]
    return wrk.format("POST", b[1], headers, b[2])
  end
end

function response(status, headers, body)
  counts[status] = (counts[status] or 0) + 1
end

function done(summary, latency, requests)
  local total = {}
  for _, t in ipairs(threads) do
    for status, n in pairs(t:get("counts")) do total[status] = (total[status] or 0) + n end
  end
  local line = "statuses:"
  for status, n in pairs(total) do line = line .. " " .. status .. "=" .. n end
  print(line)
  local e = summary.errors
  print(string.format("socket_errors: connect=%d read=%d write=%d timeout=%d",
    e.connect, e.read, e.write, e.timeout))
  print(string.format("requests=%d duration_s=%.1f rps=%.0f p50_ms=%.2f p99_ms=%.2f max_ms=%.2f",
    summary.requests, summary.duration / 1e6, summary.requests / (summary.duration / 1e6),
    latency:percentile(50) / 1e3, latency:percentile(99) / 1e3, latency.max / 1e3))
end
LUA

rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$server_pid/status" 2>/dev/null || echo 0; }
( while kill -0 "$server_pid" 2>/dev/null; do echo "$(date +%s) $(rss_kib)"; sleep 1; done ) >"$work/rss.txt" &
sampler_pid=$!

echo "== load: ${DURATION}s, $CONNECTIONS connections, mixed single/batch/inline/bad requests"
rss_start=$(rss_kib)
timeout $((DURATION + 60)) wrk -t2 -c"$CONNECTIONS" -d"${DURATION}s" --timeout 30s -s "$work/mix.lua" "$URL" \
  >"$work/load.txt" 2>&1 || fail "wrk exited non-zero"
grep -E "^(statuses|socket_errors|requests)" "$work/load.txt" | sed 's/^/   /'
kill "$sampler_pid" 2>/dev/null || true
wait "$sampler_pid" 2>/dev/null || true
sampler_pid=""

statuses=$(grep '^statuses:' "$work/load.txt" || true)
fivexx=$({ echo "$statuses" | grep -oE ' 5[0-9][0-9]=[0-9]+' || true; } | awk -F= '{s += $2} END {print s + 0}')
[ "$fivexx" -eq 0 ] || fail "$fivexx responses with a 5xx status under load"
socket_errors=$({ grep '^socket_errors:' "$work/load.txt" || true; } | { grep -oE '(connect|read|write|timeout)=[0-9]+' || true; } |
  cut -d= -f2 | awk '{s += $1} END {print s + 0}')
[ "$socket_errors" -eq 0 ] || fail "$socket_errors socket errors under load"
kill -0 "$server_pid" 2>/dev/null || fail "the server died under load"
again=$(post "/v1/geometries/$surface_id/project" '{"point":[1,2,2]}' | python3 -c 'import json,sys; print(json.load(sys.stdin)["result"]["distance"])')
[ "$again" = "$reference" ] || fail "after the load the answer changed: $reference -> $again"

# RSS: after warm-up (the first sixth of the run) it must stay flat.
samples=$(wc -l <"$work/rss.txt")
warm_line=$(( samples / 6 + 1 ))
rss_warm=$(sed -n "${warm_line}p" "$work/rss.txt" | awk '{print $2}')
rss_peak=$(awk '{if ($2 > m) m = $2} END {print m}' "$work/rss.txt")
rss_end=$(tail -n 1 "$work/rss.txt" | awk '{print $2}')
echo "   rss_kib: start=$rss_start after_warmup=$rss_warm peak=$rss_peak end=$rss_end ($samples samples)"
echo "   rss_kib over time (every ~$(( (samples + 11) / 12 ))s): $(awk -v step=$(( (samples + 11) / 12 )) '(NR - 1) % step == 0 {printf "%s ", $2}' "$work/rss.txt")"
limit=$(( rss_warm + rss_warm / 10 + 16384 ))
[ "$rss_end" -le "$limit" ] || fail "RSS grew after warm-up: $rss_warm -> $rss_end KiB (limit $limit)"

echo "== shutdown: SIGTERM under load with three ${SHUTDOWN_BATCH}-point batches in flight"
python3 - "$SHUTDOWN_BATCH" >"$work/big.json" <<'PY'
import json, random, sys
random.seed(5)
n = int(sys.argv[1])
print(json.dumps({"points": [[random.uniform(-20, 20), random.uniform(-3, 3), random.uniform(-1.5, 1.5)] for _ in range(n)]}))
PY
timeout 60 wrk -t2 -c"$CONNECTIONS" -d20s --timeout 30s -s "$work/mix.lua" "$URL" >"$work/shutdown_wrk.txt" 2>&1 &
wrk_pid=$!
sleep 2
for i in 1 2 3; do
  curl -sS --max-time 120 -o "$work/inflight$i.json" -w '%{http_code}' -H 'Content-Type: application/json' \
    --data-binary @"$work/big.json" "$URL/v1/geometries/$surface_id/project" >"$work/inflight$i.status" 2>&1 &
  eval "inflight_pid$i=$!"
done
# Signal once the three batches are being answered: their upload takes milliseconds, their
# projection seconds; the metrics count the requests in flight.
sleep 0.5
for _ in $(seq 200); do
  n=$(curl -sS --max-time 1 "$URL/metrics" 2>/dev/null | awk '/^footpoint_http_requests_in_flight / {print $2}')
  [ "${n:-0}" -ge 3 ] && break
  sleep 0.05
done
echo "   requests in flight at SIGTERM: ${n:-?}"
signal_time=$(date +%s.%N)
kill -TERM "$server_pid"
sleep 0.3
if curl -sS --max-time 2 -o /dev/null -w '%{http_code}' "$URL/healthz" >"$work/new.status" 2>"$work/new.err"; then
  code=$(cat "$work/new.status")
  if [ "$code" = "503" ]; then echo "   a new request after SIGTERM: 503"; else fail "a new request after SIGTERM got $code"; fi
else
  echo "   a new connection after SIGTERM: refused ($(head -c 80 "$work/new.err"))"
fi
exit_code=0
wait "$server_pid" || exit_code=$?
server_pid=""
stop_time=$(date +%s.%N)
echo "   exit code $exit_code, $(python3 -c "print(f'{$stop_time - $signal_time:.2f}')") s after SIGTERM"
[ "$exit_code" -eq 0 ] || fail "the server exited with $exit_code"
for i in 1 2 3; do
  eval "wait \$inflight_pid$i" || true
  status=$(cat "$work/inflight$i.status")
  answered=$(python3 -c "
import json, sys
try:
    r = json.load(open('$work/inflight$i.json'))['results']
    print(sum(1 for x in r if x['diagnostics']['status'] != 'deadline_exceeded'))
except Exception as e:
    print(0)")
  echo "   in-flight batch $i: HTTP $status, $answered of $SHUTDOWN_BATCH points answered"
  if [ "$status" != "200" ] || [ "$answered" -ne "$SHUTDOWN_BATCH" ]; then fail "in-flight batch $i did not complete"; fi
done
wait "$wrk_pid" 2>/dev/null || true
grep -E "^(statuses|socket_errors|requests)" "$work/shutdown_wrk.txt" | sed 's/^/   wrk during shutdown: /'

if [ "$failures" -eq 0 ]; then echo "load_test: PASS"; else echo "load_test: $failures check(s) FAILED"; fi
[ "$failures" -eq 0 ]
