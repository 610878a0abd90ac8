#!/usr/bin/env bash
# The server binary exposed as docs/security.md describes, driven by curl: HTTPS with a
# certificate made here by `openssl req`, plain HTTP to the TLS port refused, API keys (401 with
# WWW-Authenticate, 403, 200; the key's name in the access log, never its secret), the delete audit
# line, a per-key rate limit (429 with Retry-After), then SIGHUP with a new keys file and a new
# certificate while a batch is in flight, and SIGTERM -> exit 0.
#   bash tests/server_security_e2e.sh path/to/footpoint-server
set -euo pipefail
server=${1:?usage: server_security_e2e.sh FOOTPOINT_SERVER}
tmp=$(mktemp -d /tmp/footpoint-security.XXXXXX)
pid=""
cleanup() {
  if [ -n "$pid" ]; then kill -KILL "$pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  echo "--- server log (tail)" >&2
  tail -n 20 "$tmp/log" >&2 || true
  exit 1
}
pass() { echo "ok: $*"; }

certificate() {  # certificate NAME: $tmp/NAME.crt and $tmp/NAME.key for 127.0.0.1
  openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 2 \
    -subj "/CN=footpoint-$1" -addext subjectAltName=IP:127.0.0.1 \
    -keyout "$tmp/$1.key" -out "$tmp/$1.crt" 2>/dev/null
}
digest() { printf %s "$1" | sha256sum | cut -d' ' -f1; }
# logged [jq args...] CONDITION: some log line satisfies the jq condition
logged() { jq -s -e "${@:1:$#-1}" "any(.[]; ${!#})" "$tmp/log" >/dev/null; }

certificate first
certificate second
cp "$tmp/first.crt" "$tmp/served.crt"
cp "$tmp/first.key" "$tmp/served.key"
reader=reader-$(head -c 12 /dev/urandom | od -An -tx1 | tr -d ' \n')
builder=builder-$(head -c 12 /dev/urandom | od -An -tx1 | tr -d ' \n')
{
  echo "# test keys"
  echo "reader project $(digest "$reader")"
  echo "builder project,write,delete $(digest "$builder")"
} >"$tmp/keys"

"$server" --host 127.0.0.1 --port 0 --threads 2 --connection-threads 8 --tls-cert "$tmp/served.crt" \
  --tls-key "$tmp/served.key" --api-keys "$tmp/keys" --rate-limit 2000 --rate-burst 30000 >"$tmp/log" &
pid=$!
port=""
for _ in $(seq 100); do
  port=$(jq -r 'select(.msg == "listening") | .port' "$tmp/log" 2>/dev/null | head -n 1)
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || fail "the server did not start"
base="https://127.0.0.1:$port"
logged '.msg == "TLS certificate loaded" and (.certificate | contains("footpoint-first"))' ||
  fail "the start-up log does not name the certificate"

# status METHOD PATH [CA] [SECRET] [BODY]: the HTTP status curl got (000: no HTTP answer)
status() {
  local args=(-s -o "$tmp/body" -D "$tmp/headers" -w '%{http_code}' -X "$1" --cacert "${3:-$tmp/first.crt}")
  if [ -n "${4:-}" ]; then args+=(-H "Authorization: Bearer $4"); fi
  if [ -n "${5:-}" ]; then args+=(-H 'Content-Type: application/json' --data-binary "$5"); fi
  curl "${args[@]}" "$base$2" || true
}

[ "$(status GET /healthz)" = 200 ] || fail "GET /healthz over HTTPS"
pass "HTTPS with the certificate made by openssl"
code=$(curl -s -o /dev/null -w '%{http_code}' --max-time 5 "http://127.0.0.1:$port/healthz" || true)
[ "$code" = 000 ] || fail "plain HTTP to the TLS port answered $code"
pass "plain HTTP to the TLS port gets no HTTP answer"
if curl -s -o /dev/null --cacert "$tmp/first.crt" --tlsv1.0 --tls-max 1.1 --ciphers 'DEFAULT:@SECLEVEL=0' \
  "$base/healthz" 2>/dev/null; then
  fail "a TLS 1.1 client was served"
fi
pass "TLS 1.1 refused"

[ "$(status GET /v1/methods)" = 401 ] || fail "no key: not 401"
grep -qi '^WWW-Authenticate: Bearer' "$tmp/headers" || fail "401 without WWW-Authenticate: Bearer"
jq -e '.error.code == "missing_api_key"' "$tmp/body" >/dev/null || fail "401's JSON error"
[ "$(status GET /v1/methods "" "wrong-secret")" = 401 ] || fail "an unknown key: not 401"
[ "$(status GET /readyz)" = 200 ] || fail "/readyz needs no key"
[ "$(status GET /metrics "" "$reader")" = 403 ] || fail "/metrics without admin: not 403"
curve='{"type":"parametric_curve","x":"cos(t)","y":"2*sin(t)","domain":{"t":[0,6]}}'
[ "$(status POST /v1/geometries "" "$reader" "$curve")" = 403 ] || fail "POST a geometry with project only: not 403"
jq -e '.error.code == "insufficient_scope"' "$tmp/body" >/dev/null || fail "403's JSON error"
[ "$(status POST /v1/geometries "" "$builder" "$curve")" = 201 ] || fail "POST a geometry with write"
id=$(jq -r .geometry_id "$tmp/body")
pass "401 with WWW-Authenticate, 403 by scope, 201 with the scope"

python3 -c 'import json; print(json.dumps({"points": [[1 + i * 1e-4, 0.5] for i in range(20000)]}))' >"$tmp/points.json"
points=@$tmp/points.json
# The same points asking for the distance only: curl's --limit-rate below slows the answer too.
jq -c '. + {fields: ["distance"]}' "$tmp/points.json" >"$tmp/distances.json"
[ "$(status POST "/v1/geometries/$id/project" "" "$reader" "$points")" = 200 ] || fail "20000 points within the burst"
[ "$(status POST "/v1/geometries/$id/project" "" "$reader" "$points")" = 429 ] || fail "20000 more points: not 429"
retry=$(grep -i '^Retry-After:' "$tmp/headers" | tr -dc '0-9')
# At most 10,000 points are missing (the first batch left 10,000, refilling at 2000/s): 1 to 5 s.
if [ -z "$retry" ] || [ "$retry" -lt 1 ] || [ "$retry" -gt 5 ]; then fail "429 with Retry-After '$retry'"; fi
[ "$(status GET "/v1/geometries/$id" "" "$builder")" = 200 ] || fail "another key slowed by the reader's limit"
pass "rate limit in points: 429 with Retry-After $retry s, the other key served"

[ "$(status DELETE "/v1/geometries/$id" "" "$reader")" = 403 ] || fail "DELETE with project only: not 403"
[ "$(status DELETE "/v1/geometries/$id" "" "$builder")" = 204 ] || fail "DELETE with delete"
sleep 0.3  # the asynchronous logger
# shellcheck disable=SC2016 # $id is jq's variable
logged --arg id "$id" '.msg == "geometry deleted" and .key == "builder" and .geometry_id == $id and .level == "info"' ||
  fail "no audit line for the delete"
logged '.msg == "request" and .key == "reader" and .status == 403' || fail "the access log does not name the key"
if grep -q -e "$reader" -e "$builder" "$tmp/log"; then fail "a secret is in the log"; fi
pass "audit line for the delete, key names in the access log, no secret logged"

# SIGHUP while a batch is in flight: new keys, new certificate.
[ "$(status POST /v1/geometries "" "$builder" "$curve")" = 201 ] || fail "POST again"
newcomer=newcomer-$(head -c 12 /dev/urandom | od -An -tx1 | tr -d ' \n')
# The body (about 350 kB) is sent at 100 kB/s: the handshake with the first certificate is done
# within the first second, the request is still arriving when SIGHUP comes. The answer (the
# distances only, about 600 kB) comes back at the same rate.
curl -s -o "$tmp/in-flight" -w '%{http_code}' --limit-rate 100k --cacert "$tmp/first.crt" \
  -H "Authorization: Bearer $builder" -H 'Content-Type: application/json' --data-binary "@$tmp/distances.json" \
  "$base/v1/geometries/$id/project" >"$tmp/in-flight-status" &
flight=$!
sleep 1
echo "newcomer project $(digest "$newcomer")" >"$tmp/keys"
cp "$tmp/second.crt" "$tmp/served.crt"
cp "$tmp/second.key" "$tmp/served.key"
kill -HUP "$pid"
for _ in $(seq 50); do
  grep -q '"msg":"TLS certificate reloaded"' "$tmp/log" && break
  sleep 0.1
done
grep -q '"msg":"API keys reloaded"' "$tmp/log" || fail "no 'API keys reloaded' line"
grep -q '"msg":"TLS certificate reloaded"' "$tmp/log" || fail "no 'TLS certificate reloaded' line"
wait "$flight" || fail "curl's batch in flight during SIGHUP failed: exit $?"
[ "$(cat "$tmp/in-flight-status")" = 200 ] || fail "the batch in flight during SIGHUP got $(cat "$tmp/in-flight-status")"
sleep 0.3  # the asynchronous logger
reloaded_at=$(grep -n '"msg":"TLS certificate reloaded"' "$tmp/log" | cut -d: -f1)
answered_at=$(grep -n '"points":20000,.*"key":"builder"' "$tmp/log" | tail -n 1 | cut -d: -f1)
[ "${answered_at:-0}" -gt "$reloaded_at" ] || fail "the batch was answered before the reload, not during it"
[ "$(status GET /healthz "$tmp/second.crt")" = 200 ] || fail "the new certificate is not served"
[ "$(status GET /healthz "$tmp/first.crt")" = 000 ] || fail "the old certificate is still served"
[ "$(status GET /v1/methods "$tmp/second.crt" "$newcomer")" = 200 ] || fail "the new key is refused"
[ "$(status GET /v1/methods "$tmp/second.crt" "$reader")" = 401 ] || fail "the removed key is accepted"
kill -0 "$pid" || fail "the server exited on SIGHUP"
pass "SIGHUP: new keys and certificate, the batch in flight answered 200"

kill -TERM "$pid"
set +e
wait "$pid"
rc=$?
set -e
pid=""
[ "$rc" = 0 ] || fail "exit code $rc after SIGTERM"
pass "SIGTERM: exit 0"
