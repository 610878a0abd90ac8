#!/usr/bin/env bash
# The container's runtime layout, tested without a Docker engine: installs an existing build into a
# staging prefix with the Dockerfile's install step (cmake --install <build> --prefix <stage>
# --component server --strip), checks that the runtime stage's packages provide every library the
# installed server links, then starts the installed server the way the image does (from the prefix, configured by
# environment only, as uid 10001 and with the source and build trees hidden when this runs as root
# with mount namespaces available) on a free loopback port and checks /healthz, /readyz, /metrics,
# /openapi.yaml, projections with known answers, examples/project_csv.sh, the operations section's
# curl examples, the request log line, and that SIGTERM during a batch lets the batch finish and
# ends the server with exit code 0.
#
#   deploy/check_layout.sh BUILD_DIR     (BUILD_DIR holds a built footpoint-server)
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
deploy=$(cd "$(dirname "$0")" && pwd)
source_dir=$(dirname "$deploy")
python=/usr/bin/python3

fail() {
  echo "FAIL: $*" >&2
  if [ -n "${server_log:-}" ] && [ -f "$server_log" ]; then
    echo "--- server output (last 20 lines) ---" >&2
    tail -n 20 "$server_log" >&2
  fi
  exit 1
}
pass() { echo "ok: $*"; }

tmp=$(mktemp -d /tmp/footpoint-layout.XXXXXX)
server_pid=
client_pid=
replica_pid=
proxy_pid=
redis_pid=
cleanup() {
  if [ -n "$server_pid" ] && kill -0 "$server_pid" 2>/dev/null; then
    kill -KILL "$server_pid" 2>/dev/null || true
    wait "$server_pid" 2>/dev/null || true
  fi
  # shellcheck disable=SC2086  # replica_pid holds several pids
  for pid in $client_pid $replica_pid $proxy_pid $redis_pid; do
    kill "$pid" 2>/dev/null || true
  done
  rm -rf "$tmp"
}
trap cleanup EXIT
chmod 755 "$tmp"
stage=$tmp/stage

# ---- 0. the build stage's context configures --------------------------------------------------------
# The build stage sees only what it COPYs (and deploy/Dockerfile.dockerignore lets through):
# configure exactly that tree with the Dockerfile's -D flags, so that a new top-level folder the
# build needs cannot silently break the image. (Configure only; the build itself is the one in BUILD_DIR.)
context=$tmp/context
mkdir -p "$context"
build_stage=$(awk '/^FROM /{n++} n == 1' "$deploy/Dockerfile")
while read -r -a words; do
  for src in "${words[@]:1:${#words[@]}-2}"; do cp -r "$source_dir/$src" "$context/"; done
done < <(grep '^COPY ' <<< "$build_stage" | grep -v -- '--from=')
context_files=$(cd "$context" && printf '%s ' *)
read -r -a cmake_flags <<< "$(grep -o -- '-D[A-Z_]*=[A-Za-z0-9_]*' <<< "$build_stage" | tr '\n' ' ')"
cmake -S "$context" -B "$context/build" "${cmake_flags[@]}" > "$tmp/context.log" 2>&1 ||
  { cat "$tmp/context.log"; fail "the build stage's context ($context_files) does not configure"; }
targets=$(cmake --build "$context/build" --target help)
grep -q 'footpoint-server' <<< "$targets" ||
  fail "the build stage's context configures without the footpoint-server target"
pass "the build stage's context ($context_files) configures with ${cmake_flags[*]}"

# ---- 1. the install step of deploy/Dockerfile -----------------------------------------------------
prefix_in_image=$(sed -n 's/.*cmake --install [^ ]* --prefix \([^ ]*\).*/\1/p' "$deploy/Dockerfile" | head -n 1)
[ -n "$prefix_in_image" ] || fail "deploy/Dockerfile has no 'cmake --install <build> --prefix <dir>' step"
# The image holds the install component the Dockerfile names (the server, not the core library's
# headers and static libraries).
component=$(sed -n 's/.*cmake --install .* --component \([^ ]*\).*/\1/p' "$deploy/Dockerfile" | head -n 1)
[ "$component" = server ] || fail "deploy/Dockerfile does not install the component server (cmake --install ... --component server)"
cmake --install "$build" --prefix "$stage" --component "$component" --strip > "$tmp/install.log" ||
  { cat "$tmp/install.log"; fail "cmake --install"; }
[ ! -e "$stage/include" ] || fail "the server component installs the core library's headers"
server=$stage/bin/footpoint-server
entrypoint=$(sed -n 's/^ENTRYPOINT \["\([^"]*\)".*/\1/p' "$deploy/Dockerfile")
[ "$entrypoint" = "$prefix_in_image/bin/footpoint-server" ] ||
  fail "ENTRYPOINT $entrypoint is not the installed $prefix_in_image/bin/footpoint-server"
[ -x "$server" ] || fail "the install step did not produce bin/footpoint-server"
[ -f "$stage/share/footpoint/openapi.yaml" ] || fail "the install step did not produce share/footpoint/openapi.yaml"
pass "cmake --install into a staging prefix: $(cd "$stage" && find . -type f | sort | tr '\n' ' ')"

# ---- 2. the runtime stage provides every library the server links --------------------------------
"$python" "$deploy/check_manifests.py" --binary "$server" > "$tmp/manifests.log" ||
  { cat "$tmp/manifests.log"; fail "runtime libraries or manifests"; }
pass "runtime stage packages cover ldd $(ldd "$server" | grep -c '=>') libraries"

# ---- 3. start the installed server as the image does ------------------------------------------------
port=$("$python" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
server_log=$tmp/server.log
launch=(env -i PATH=/usr/bin:/bin FOOTPOINT_HOST=127.0.0.1 FOOTPOINT_PORT="$port" FOOTPOINT_THREADS=2
        FOOTPOINT_LOG_LEVEL=info "$server")
how="as uid $(id -u), source tree visible"
if [ "$(id -u)" = 0 ] && unshare -m --propagation private true 2>/dev/null && command -v setpriv > /dev/null; then
  # A private mount namespace hides the source and build trees (the image has neither); setpriv
  # drops to the image's uid. exec keeps one pid from unshare to the server.
  hide="mount -t tmpfs -o ro,size=4k none '$source_dir'"
  case "$build" in "$source_dir"/*) ;; *) hide="$hide && mount -t tmpfs -o ro,size=4k none '$build'" ;; esac
  cd /
  unshare -m --propagation private sh -c "$hide && exec setpriv --reuid=10001 --regid=10001 --clear-groups \"\$@\"" \
    sh "${launch[@]}" > "$server_log" 2>&1 &
  server_pid=$!
  how="as uid 10001, source and build trees hidden"
else
  (cd / && exec "${launch[@]}") > "$server_log" 2>&1 &
  server_pid=$!
fi
base=http://127.0.0.1:$port
for _ in $(seq 1 100); do
  curl -sf -o /dev/null "$base/healthz" && break
  kill -0 "$server_pid" 2>/dev/null || fail "the installed server exited at start"
  sleep 0.1
done
curl -sf -o /dev/null "$base/healthz" || fail "/healthz did not answer 200 within 10 s"
pass "installed server started ($how) on 127.0.0.1:$port, /healthz 200"

# ---- 4. what the probes, Prometheus and clients see -------------------------------------------------
status=$(curl -s -o /dev/null -w '%{http_code}' "$base/readyz")
[ "$status" = 200 ] || fail "/readyz answered $status"
pass "/readyz 200"
curl -sf "$base/openapi.yaml" | cmp -s - "$stage/share/footpoint/openapi.yaml" ||
  fail "/openapi.yaml differs from the installed share/footpoint/openapi.yaml"
pass "/openapi.yaml equals the installed copy"

# A plane z = 0 and the unit circle: the foot points are known exactly.
answer=$(curl -sf "$base/v1/project" -H 'Content-Type: application/json' -H 'X-Request-Id: layout-check-1' -d '{
  "geometry": {"type": "parametric_surface", "x": "u", "y": "v", "z": "0", "domain": {"u": [-1, 1], "v": [-1, 1]}},
  "point": [0.25, -0.5, 2]}') || fail "POST /v1/project (surface)"
echo "$answer" | jq -e '.result.foot_point == [0.25, -0.5, 0] and .result.distance == 2
  and .result.diagnostics.status == "converged"' > /dev/null || fail "plane projection: $answer"
answer=$(curl -sf "$base/v1/project" -H 'Content-Type: application/json' -d '{
  "geometry": {"type": "parametric_curve", "x": "cos(t)", "y": "sin(t)", "domain": {"t": [-3, 3]}},
  "points": [[2, 0], [0, 0.5]]}') || fail "POST /v1/project (curve batch)"
echo "$answer" | jq -e '(.results | length) == 2
  and ([.results[0].foot_point[0] - 1, .results[0].foot_point[1], .results[0].distance - 1,
        .results[1].foot_point[0], .results[1].foot_point[1] - 1, .results[1].distance - 0.5]
       | map(fabs) | max) < 1e-14' > /dev/null || fail "circle projection: $answer"
pass "projections onto a plane and a circle match the exact answers"

# The operator's view: one JSON log line per request with its id, and the request counters.
for _ in $(seq 1 20); do grep -q '"request_id":"layout-check-1"' "$server_log" && break; sleep 0.1; done
grep '"request_id":"layout-check-1"' "$server_log" | jq -e '.msg == "request" and .status == 200
  and .route == "/v1/project" and .points == 1' > /dev/null || fail "no JSON request log line for layout-check-1"
metrics=$(curl -sf "$base/metrics") || fail "GET /metrics"
grep -q '^footpoint_http_requests_total{route="/v1/project",status="200"} 2$' <<< "$metrics" ||
  fail "/metrics does not count the two /v1/project requests"
pass "JSON request log line and /metrics counters"

# ---- 5. the example client against the staged server ----------------------------------------------
FOOTPOINT_URL=$base "$source_dir/examples/project_csv.sh" "$source_dir/examples/torus.json" \
  "$source_dir/examples/points.csv" 4 > "$tmp/feet.csv" || fail "examples/project_csv.sh"
# Torus with radii R = 2, r = 0.5: the nearest point of the tube's centre circle is
# c = R (x, y, 0) / |(x, y)|, the foot point c + r (p - c) / |p - c|, the distance ||p - c| - r|.
"$python" - "$source_dir/examples/points.csv" "$tmp/feet.csv" <<'EOF' || fail "examples/project_csv.sh output"
import csv, math, sys
lines = list(csv.reader(open(sys.argv[1])))
points = [(n, list(map(float, row))) for n, row in enumerate(lines, 1) if row and row[0][0] in "-+.0123456789"]
rows = list(csv.reader(open(sys.argv[2])))
assert rows[0] == ["line", "foot_x", "foot_y", "foot_z", "distance", "status", "u", "v"], rows[0]
assert len(rows) == len(points) + 1, (len(rows), len(points))
worst = 0.0
for (n, p), row in zip(points, rows[1:]):
    assert int(row[0]) == n, (row[0], n)  # the point's line in the input
    rho = math.hypot(p[0], p[1])
    c = [2 * p[0] / rho, 2 * p[1] / rho, 0.0]
    d = math.dist(p, c)
    foot = [c[i] + 0.5 * (p[i] - c[i]) / d for i in range(3)]
    assert row[5] == "converged", row
    # the parameters give the foot point through the torus's formulas
    u, v = float(row[6]), float(row[7])
    at = [(2 + 0.5 * math.cos(v)) * math.cos(u), (2 + 0.5 * math.cos(v)) * math.sin(u), 0.5 * math.sin(v)]
    worst = max(worst, abs(float(row[4]) - abs(d - 0.5)), max(abs(float(row[1 + i]) - foot[i]) for i in range(3)),
                max(abs(at[i] - foot[i]) for i in range(3)))
assert worst < 1e-12, worst
print(f"ok: examples/project_csv.sh: {len(points)} points in batches of 4, their lines and parameters, max error {worst:.1e} against the exact torus foot points")
EOF
# What it says of a file it cannot read as points: a header alone, spaces or semicolons.
printf 'x,y,z\n# nothing else\n' > "$tmp/header-only.csv"
printf 'x y z\n1 2 3\n' > "$tmp/spaces.csv"
printf 'x;y;z\n1;2;0,5\n' > "$tmp/semicolons.csv"
for case in "header-only:holds no point" "spaces:line 2: '1 2 3' is separated by spaces" \
  "semicolons:line 2: '1;2;0,5' is separated by semicolons"; do
  file=${case%%:*}
  expected=${case#*:}
  if FOOTPOINT_URL=$base "$source_dir/examples/project_csv.sh" "$source_dir/examples/torus.json" "$tmp/$file.csv" \
    > /dev/null 2> "$tmp/$file.err"; then
    fail "examples/project_csv.sh accepted $file.csv"
  fi
  grep -qF "$expected" "$tmp/$file.err" || fail "examples/project_csv.sh on $file.csv said: $(cat "$tmp/$file.err")"
done
pass "examples/project_csv.sh names the problem of a header-only, a space- and a semicolon-separated file"

# Scale-out: two replicas behind a round-robin proxy (one backend per connection; curl opens one
# per request), so the geometry is posted to one replica and every batch lands on the other. With
# the shared registry (a redis-server of this check's own, on loopback with a password) the other
# replica answers the id itself: no batch may need the script's fallback to /v1/project, and the
# output must be the same bytes as against one server. Without redis-server installed the check
# runs the replicas without a registry and expects the fallback instead (each batch meets 404).
free_port() { "$python" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
registry_env=()
if command -v redis-server > /dev/null; then
  redis_port=$(free_port)
  redis_password=layout-$RANDOM-$RANDOM
  mkdir -p "$tmp/redis"
  redis-server --port "$redis_port" --bind 127.0.0.1 --save '' --appendonly no --dir "$tmp/redis" \
    --requirepass "$redis_password" > "$tmp/redis.log" 2>&1 &
  redis_pid=$!
  for _ in $(seq 1 100); do
    REDISCLI_AUTH=$redis_password redis-cli -p "$redis_port" ping 2>/dev/null | grep -q PONG && break
    sleep 0.05
  done
  registry_env=(FOOTPOINT_REGISTRY_URL="redis://127.0.0.1:$redis_port/0" FOOTPOINT_REGISTRY_PASSWORD="$redis_password")
else
  echo "note: redis-server is not installed: the scale-out check runs without the shared registry"
fi
replica_ports=()
replica_pids=()
for r in a b; do
  replica_port=$(free_port)
  (cd / && exec env -i PATH=/usr/bin:/bin FOOTPOINT_HOST=127.0.0.1 FOOTPOINT_PORT="$replica_port" FOOTPOINT_THREADS=1 \
    "${registry_env[@]}" "$server") > "$tmp/replica-$r.log" 2>&1 &
  replica_pids+=($!)
  replica_ports+=("$replica_port")
  replica_pid="${replica_pids[*]}"
  for _ in $(seq 1 100); do curl -sf -o /dev/null "http://127.0.0.1:$replica_port/healthz" && break; sleep 0.1; done
  curl -sf -o /dev/null "http://127.0.0.1:$replica_port/healthz" || fail "replica $r did not start"
done
"$python" - "${replica_ports[@]}" > "$tmp/proxy.port" <<'EOF' &
import itertools, socket, sys, threading
backends = itertools.cycle([("127.0.0.1", int(p)) for p in sys.argv[1:]])
listener = socket.create_server(("127.0.0.1", 0))
listener.settimeout(60)  # ends by itself once idle
print(listener.getsockname()[1], flush=True)

def pipe(src, dst):
    try:
        while data := src.recv(65536):
            dst.sendall(data)
    except OSError:
        pass
    finally:
        try:
            dst.shutdown(socket.SHUT_WR)
        except OSError:
            pass

while True:
    try:
        client, _ = listener.accept()
    except socket.timeout:
        break
    upstream = socket.create_connection(next(backends))
    for a, b in ((client, upstream), (upstream, client)):
        threading.Thread(target=pipe, args=(a, b), daemon=True).start()
EOF
proxy_pid=$!
for _ in $(seq 1 50); do [ -s "$tmp/proxy.port" ] && break; sleep 0.1; done
FOOTPOINT_URL=http://127.0.0.1:$(cat "$tmp/proxy.port") "$source_dir/examples/project_csv.sh" \
  "$source_dir/examples/torus.json" "$source_dir/examples/points.csv" 4 > "$tmp/feet-balanced.csv" ||
  fail "examples/project_csv.sh behind the round-robin proxy"
cmp -s "$tmp/feet.csv" "$tmp/feet-balanced.csv" || fail "two replicas answered differently from one"
for pid in "${replica_pids[@]}"; do
  kill -TERM "$pid"
  wait "$pid" || fail "a replica did not exit 0 on SIGTERM"
done
replica_pid=
kill "$proxy_pid" 2>/dev/null || true
wait "$proxy_pid" 2>/dev/null || true
proxy_pid=
count() { cat "$tmp"/replica-*.log | grep -c "$1" || true; }
by_id=$(count '"route":"/v1/geometries/{id}/project","status":200')
misses=$(count '"route":"/v1/geometries/{id}/project","status":404')
oneshot=$(count '"route":"/v1/project"')
if [ ${#registry_env[@]} -gt 0 ]; then
  kill "$redis_pid" 2>/dev/null || true
  wait "$redis_pid" 2>/dev/null || true
  redis_pid=
  if [ "$by_id" != 3 ] || [ "$misses" != 0 ] || [ "$oneshot" != 0 ]; then
    fail "with the registry, expected 3 batches answered by id and no retry; saw $by_id by id, $misses 404, $oneshot one-shot"
  fi
  pass "two replicas on a shared registry behind a round-robin proxy: 3 batches answered by id by the replica that did not see the post, no client retry, same output"
else
  if [ "$misses" != 3 ] || [ "$oneshot" != 3 ]; then
    fail "without a registry, expected 3 geometry_not_found answers and 3 one-shot retries; saw $misses and $oneshot"
  fi
  pass "two replicas without a registry behind a round-robin proxy: 3 batches met an unknown id (404), went to /v1/project, same output"
fi

# The copy-paste curl examples of the documentation (the API by example, Results, Formulas) and
# the operations section's configuration table.
"$python" "$deploy/check_examples.py" --server "$server" "$base" "$source_dir/docs/api.md" \
  "$source_dir/docs/formulas.md" "$source_dir/docs/operations.md" ||
  fail "the documentation's curl examples"

# ---- 6. SIGTERM: the request in flight is answered in full, then exit code 0 -----------------------
"$python" - "$source_dir/examples/torus.json" > "$tmp/batch.json" <<'EOF'
import json, random, sys
random.seed(6)
points = [[random.uniform(-3, 3), random.uniform(-3, 3), random.uniform(-1, 1)] for _ in range(50000)]
print(json.dumps({"geometry": json.load(open(sys.argv[1])), "points": points}))
EOF
curl -s -o "$tmp/batch.out" -w '%{http_code}' "$base/v1/project" -H 'Content-Type: application/json' \
  --data-binary "@$tmp/batch.json" > "$tmp/batch.status" &
client_pid=$!
in_flight=0
for _ in $(seq 1 500); do
  in_flight=$(curl -sf "$base/metrics" | sed -n 's/^footpoint_http_requests_in_flight \([0-9]*\)$/\1/p' || true)
  [ "${in_flight:-0}" -ge 1 ] && break
  kill -0 "$client_pid" 2>/dev/null || break
  sleep 0.01
done
kill -TERM "$server_pid"
for _ in $(seq 1 150); do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.1; done
kill -0 "$server_pid" 2>/dev/null && fail "the server did not stop within 15 s of SIGTERM"
set +e
wait "$server_pid"
code=$?
set -e
server_pid=
[ "$code" = 0 ] || fail "the server exited with code $code after SIGTERM"
wait "$client_pid" || fail "the client of the in-flight batch failed"
client_pid=
if [ "${in_flight:-0}" -ge 1 ]; then
  if [ "$(cat "$tmp/batch.status")" != 200 ] || ! jq -e '(.results | length) == 50000' "$tmp/batch.out" > /dev/null; then
    fail "the batch in flight at SIGTERM was not answered in full: HTTP $(cat "$tmp/batch.status")"
  fi
  pass "SIGTERM during a 50,000-point batch: the batch answered in full (200), then exit code 0"
else
  pass "SIGTERM: exit code 0 (the batch finished before it could be seen in flight)"
fi
echo "PASS: deploy layout"
