#!/usr/bin/env bash
# Deadlines on loopback (127.0.0.1 only): no request may hold the server past its deadline.
#   bench/deadline_test.sh [BUILD_DIR]     (BUILD_DIR/footpoint-server, Release; default build)
# Environment: DEADLINE_MS (the server's --deadline-ms, default 1000), SLACK_MS (allowed beyond
# it for reading the body, writing the answer and the points already started, default 1000),
# PORT (default 18495).
# Each request below must be answered within DEADLINE_MS + SLACK_MS, and a good request sent
# right after it must be answered at once (< 500 ms) with the reference answer:
#   - a huge batch: 100,000 points, [Curve] Example 2 with its slowest method
#     ("complete") and the largest iteration budget (minutes of work);
#   - pathological formulas, each posted once (so compiled, with everything `auto` precomputes,
#     inside the request): a 4,000-character sum of sines as a parametric curve over a long
#     domain, the same as a surface, and high-degree implicit equations over a large box.
# Exit status 0 when every request met its deadline.
set -euo pipefail

if [ -z "${FOOTPOINT_DEADLINE_TEST_BOUNDED:-}" ]; then
  export FOOTPOINT_DEADLINE_TEST_BOUNDED=1
  exec timeout --kill-after=10 900 "$0" "$@"
fi

BUILD=${1:-build}
DEADLINE_MS=${DEADLINE_MS:-1000}
SLACK_MS=${SLACK_MS:-1000}
PORT=${PORT:-18495}
URL="http://127.0.0.1:$PORT"
SERVER="$BUILD/footpoint-server"
for tool in curl python3; do command -v "$tool" >/dev/null || { echo "deadline_test: $tool is required" >&2; exit 2; }; done
[ -x "$SERVER" ] || { echo "deadline_test: $SERVER not built" >&2; exit 2; }

work=$(mktemp -d)
server_pid=""
cleanup() {
  if [ -n "$server_pid" ]; then kill -TERM "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 143' TERM INT

"$SERVER" --host 127.0.0.1 --port "$PORT" --log-level warn --deadline-ms "$DEADLINE_MS" >"$work/server.log" 2>&1 &
server_pid=$!
for _ in $(seq 100); do
  curl -fsS --max-time 1 "$URL/healthz" >/dev/null 2>&1 && break
  sleep 0.1
done

# The request bodies (a random salt in each pathological formula: a new geometry every run).
python3 - "$work" <<'PY'
import json, random, sys
work = sys.argv[1]
random.seed()
salt = random.randint(1, 10**9)
sines = lambda a, b: "+".join(f"sin({k}*{a}+{k % 5}*{b})" for k in range(1, 120))[:3990] + f"+{salt}e-12"
c2 = {"type": "implicit_curve", "equations": ["x^2/9+y^2/16+z^2/9+4*x*y-1", "x^2+y^2+x-4*z"],
      "domain": {"x": [-300, 300], "y": [-300, 300], "z": [-300, 300]}}
rng = random.Random(3)
cases = {
    "huge batch (100,000 points, method complete, 10,000 iterations)":
        {"geometry": c2, "points": [[rng.uniform(-400, 400) for _ in range(3)] for _ in range(100000)],
         "method": "complete", "options": {"max_iterations": 10000}},
    "pathological parametric curve (4,000-character sum of sines, t in [-1000, 1000])":
        {"geometry": {"type": "parametric_curve", "x": sines("t", "t"), "y": "t", "domain": {"t": [-1000, 1000]}},
         "point": [1, 2]},
    "pathological surface (4,000-character sum of sines over [-300, 300]^2)":
        {"geometry": {"type": "parametric_surface", "x": sines("u", "v"), "y": "v", "z": "u",
                      "domain": {"u": [-300, 300], "v": [-300, 300]}}, "point": [1, 2, 3]},
    "pathological implicit curve (degree 9 and 7 over a 900-wide box)":
        {"geometry": {"type": "implicit_curve", "equations": [f"x^9/9+y^2/16+z^2/9-1-{salt}e-15", "x^7+y^2-4*z"],
                      "domain": {"x": [-600, 300], "y": [-380, 380], "z": [-300, 300]}}, "point": [1, 2, 3]},
}
for i, (name, body) in enumerate(cases.items()):
    with open(f"{work}/case{i}.json", "w") as f:
        json.dump(body, f)
    with open(f"{work}/case{i}.name", "w") as f:
        f.write(name)
PY

surface='{"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}}'
id=$(curl -sS -H 'Content-Type: application/json' --data-binary "$surface" "$URL/v1/geometries" |
  python3 -c 'import json,sys; print(json.load(sys.stdin)["geometry_id"])')
good() {  # prints "seconds distance" for the [GSA] Example 1 point
  curl -sS -o "$work/good.json" -w '%{time_total}' -H 'Content-Type: application/json' \
    --data-binary '{"point":[1,2,2]}' "$URL/v1/geometries/$id/project" >"$work/good.time"
  python3 -c "import json; print(open('$work/good.time').read(), json.load(open('$work/good.json'))['result']['distance'])"
}
reference=$(good | awk '{print $2}')

failures=0
limit=$(python3 -c "print(($DEADLINE_MS + $SLACK_MS) / 1000)")
echo "deadline ${DEADLINE_MS} ms, limit ${limit} s per request"
for body in "$work"/case*.json; do
  name=$(cat "${body%.json}.name")
  seconds=$(curl -sS --max-time 600 -o "$work/answer.json" -w '%{time_total}' -H 'Content-Type: application/json' \
    --data-binary @"$body" "$URL/v1/project" || echo 600)
  summary=$(python3 - "$work/answer.json" <<'PY'
import collections, json, sys
try:
    a = json.load(open(sys.argv[1]))
except Exception:
    print("no JSON answer"); sys.exit()
if "error" in a:
    print("error " + a["error"]["code"]); sys.exit()
results = a["results"] if "results" in a else [a["result"]]
print(", ".join(f"{s} {n}" for s, n in collections.Counter(r["diagnostics"]["status"] for r in results).most_common()))
PY
)
  read -r good_seconds good_distance <<<"$(good)"
  verdict=ok
  below() { python3 -c "import sys; sys.exit(0 if $1 <= $2 else 1)"; }
  if ! below "$seconds" "$limit"; then verdict="OVER THE DEADLINE"; failures=$((failures + 1)); fi
  if [ "$good_distance" != "$reference" ]; then verdict="$verdict; good answer changed"; failures=$((failures + 1)); fi
  if ! below "$good_seconds" 0.5; then verdict="$verdict; good request slow"; failures=$((failures + 1)); fi
  printf '%-85s %7.2f s  %-8s [%s] then a good request in %.3f s\n' "$name" "$seconds" "$verdict" "$summary" "$good_seconds"
done
if [ "$failures" -eq 0 ]; then echo "deadline_test: PASS"; else echo "deadline_test: $failures check(s) FAILED"; fi
[ "$failures" -eq 0 ]
