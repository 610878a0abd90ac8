#!/usr/bin/env bash
# Projects a CSV of points onto a geometry through a running footpoint service, with curl and jq.
#
#   examples/project_csv.sh GEOMETRY.json POINTS.csv [BATCH_SIZE] > feet.csv
#   FOOTPOINT_URL=http://footpoint:8080 examples/project_csv.sh examples/torus.json examples/points.csv
#
# POINTS.csv: one point per line, "x,y,z" (or "x,y" for a planar curve); lines that do not start
# with a number (a header, comments) are skipped. Output, in input order:
#   foot_x,foot_y[,foot_z],distance,status
#
# The geometry is posted once (POST /v1/geometries answers its id, a hash of the definition); the
# points go in batches to POST /v1/geometries/{id}/project, which carries no definition. With a
# shared registry every replica answers the id. Without one, behind a load balancer, a batch can
# land on a replica that has not seen the id (404 geometry_not_found), and with one a replica
# that does not hold the id can find the registry unreachable (503 registry_unavailable): that
# batch goes again to the one-shot POST /v1/project with the definition inline, which any replica
# answers, and which leaves the geometry cached there under the same id.
set -euo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  sed -n '2,9p' "$0" >&2
  exit 2
fi
geometry_file=$1
points_file=$2
batch_size=${3:-1000}
url=${FOOTPOINT_URL:-http://localhost:8080}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# POSTs a JSON file; prints the HTTP status, leaves the body in $work/response.json.
post() {
  curl -sS -o "$work/response.json" -w '%{http_code}' -X POST "$url$1" \
    -H 'Content-Type: application/json' --data-binary "@$2"
}

fail() {
  echo "project_csv.sh: $1 (HTTP $2):" >&2
  jq -c '.error // .' "$work/response.json" >&2 || cat "$work/response.json" >&2
  exit 1
}

status=$(post /v1/geometries "$geometry_file")
case $status in 200 | 201) ;; *) fail "the geometry was refused" "$status" ;; esac
id=$(jq -r '.geometry_id' "$work/response.json")

# Numeric lines only, split into batches of $batch_size lines.
grep -E '^[[:space:]]*[-+.0-9]' "$points_file" | split -l "$batch_size" -a 6 - "$work/batch."

first=1
for batch in "$work"/batch.*; do
  # "1,2,3" lines -> {"points": [[1,2,3], ...]}
  jq -R -s '{points: (split("\n") | map(select(length > 0) | split(",") | map(tonumber)))}' \
    "$batch" > "$work/request.json"
  status=$(post "/v1/geometries/$id/project" "$work/request.json")
  code=$(jq -r '.error.code // empty' "$work/response.json")
  if { [ "$status" = 404 ] && [ "$code" = geometry_not_found ]; } ||
     { [ "$status" = 503 ] && [ "$code" = registry_unavailable ]; }; then
    jq --slurpfile geometry "$geometry_file" '{geometry: $geometry[0]} + .' "$work/request.json" > "$work/oneshot.json"
    status=$(post /v1/project "$work/oneshot.json")
  fi
  [ "$status" = 200 ] || fail "a batch was refused" "$status"
  if [ $first = 1 ]; then
    jq -r '.results[0].foot_point | length | if . == 2 then "foot_x,foot_y,distance,status"
           else "foot_x,foot_y,foot_z,distance,status" end' "$work/response.json"
    first=0
  fi
  jq -r '.results[] | [.foot_point[], .distance, .diagnostics.status] | map(tostring) | join(",")' \
    "$work/response.json"
done
