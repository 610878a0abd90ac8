#!/usr/bin/env bash
# Memory of one 100,000-point batch: footpoint-server (default settings, on 127.0.0.1) projects
# POINTS points (default 100000, the largest batch --max-points allows) on the [GSA] Example 1
# surface over [-3,3]^2, REPEATS times (default 3); printed: the resident size after the geometry
# is compiled (baseline), the peak resident size after each batch (VmHWM, /proc/PID/status), and
# the peak less the baseline. Freed request buffers are kept for the next request (README,
# Memory), so later batches reuse the first one's pages.
#   bench/batch_memory.sh [BUILD_DIR]      (default build)
set -euo pipefail
BUILD=${1:-build}
POINTS=${POINTS:-100000}
REPEATS=${REPEATS:-3}
PORT=${PORT:-18491}
HOST=127.0.0.1
SERVER="$BUILD/footpoint-server"
[ -x "$SERVER" ] || { echo "batch_memory: $SERVER not built" >&2; exit 2; }
command -v curl >/dev/null || { echo "batch_memory: curl is required" >&2; exit 2; }

work=$(mktemp -d)
pid=
cleanup() {
  [ -n "$pid" ] && kill -TERM "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

"$SERVER" --host "$HOST" --port "$PORT" --log-level warn >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do
  curl -fsS --max-time 1 "http://$HOST:$PORT/healthz" >/dev/null 2>&1 && break
  sleep 0.1
done
kib() { awk -v k="$1" '$1 == k":" {print $2}' "/proc/$pid/status"; }

surface='{"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-3,3],"v":[-3,3]}}'
id=$(curl -fsS --max-time 30 -H 'Content-Type: application/json' -d "$surface" "http://$HOST:$PORT/v1/geometries" |
  sed -E 's/.*"geometry_id":"([0-9a-f]+)".*/\1/')
awk -v n="$POINTS" 'BEGIN {
  srand(11)
  printf "{\"points\":["
  for (i = 0; i < n; ++i)
    printf "%s[%.17g,%.17g,%.17g]", (i ? "," : ""), rand() * 40 - 20, rand() * 6 - 3, rand() * 3 - 1.5
  printf "]}"
}' >"$work/batch.json"
base=$(kib VmRSS)
printf 'batch_memory: %d points per batch, body %.1f MiB; resident after compiling: %.1f MiB\n' \
  "$POINTS" "$(stat -c %s "$work/batch.json" | awk '{print $1 / 1048576}')" "$(awk -v k="$base" 'BEGIN {print k / 1024}')"
for r in $(seq "$REPEATS"); do
  curl -fsS --max-time 300 -H 'Content-Type: application/json' --data-binary "@$work/batch.json" \
    -o "$work/answer.json" "http://$HOST:$PORT/v1/geometries/$id/project"
  peak=$(kib VmHWM)
  printf 'batch %d: answer %.1f MiB, peak resident %.1f MiB, %.1f MiB above the baseline\n' "$r" \
    "$(stat -c %s "$work/answer.json" | awk '{print $1 / 1048576}')" "$(awk -v k="$peak" 'BEGIN {print k / 1024}')" \
    "$(awk -v k="$peak" -v b="$base" 'BEGIN {print (k - b) / 1024}')"
done
