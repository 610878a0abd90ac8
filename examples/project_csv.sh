#!/usr/bin/env bash
# Projects a CSV of points onto a geometry through a running footpoint service, with curl and jq.
#
#   examples/project_csv.sh GEOMETRY.json POINTS.csv [BATCH_SIZE] > feet.csv
#   FOOTPOINT_URL=http://footpoint:8080 examples/project_csv.sh examples/torus.json examples/points.csv
#
# POINTS.csv: one point per line, "x,y,z" (or "x,y" for a planar curve), comma-separated; lines
# that do not start with a number (a header, comments) are skipped. Output, in input order:
#   line,foot_x,foot_y[,foot_z],distance,status[,u,v | ,t]
# line: the point's line in POINTS.csv (from 1, the header counted); u,v (surfaces) or t
# (parametric curves): the foot point's parameters (implicit curves have none).
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
  sed -n '2,11p' "$0" >&2
  exit 2
fi
geometry_file=$1
points_file=$2
batch_size=${3:-1000}
url=${FOOTPOINT_URL:-http://localhost:8080}

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

usage_error() {
  echo "project_csv.sh: $1" >&2
  exit 2
}

# The numeric lines with their line numbers ("12:1.5,2,3"), checked before anything is sent.
[ -r "$points_file" ] || usage_error "cannot read $points_file"
grep -nE '^[[:space:]]*[-+.0-9]' "$points_file" > "$work/points" || true
if [ ! -s "$work/points" ]; then
  usage_error "$points_file holds no point: no line starts with a number (a header or comments only?); write one point per line, x,y,z"
fi
# The first line that is not comma-separated numbers says how it is separated instead.
bad=$(grep -vE '^[0-9]+:[[:space:]]*[-+.0-9eE]+([[:space:]]*,[[:space:]]*[-+.0-9eE]+){1,2}[[:space:]]*$' "$work/points" | head -n 1 || true)
if [ -n "$bad" ]; then
  number=${bad%%:*}
  text=${bad#*:}
  case $text in
    *';'*) how="semicolons" ;;
    *,*) how="commas, but not as 2 or 3 numbers" ;;
    *[[:space:]]*[0-9]*) how="spaces" ;;
    *) how="nothing (one number)" ;;
  esac
  usage_error "$points_file line $number: '$text' is separated by $how; write x,y,z (or x,y) with commas between the coordinates and '.' as the decimal point"
fi

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
dim=$(jq -r '.point_dim' "$work/response.json")
params=$(jq -r '.num_params' "$work/response.json")
header="line,foot_x,foot_y"
[ "$dim" = 3 ] && header="$header,foot_z"
header="$header,distance,status"
case $params in 2) header="$header,u,v" ;; 1) header="$header,t" ;; esac
echo "$header"

split -l "$batch_size" -a 6 "$work/points" "$work/batch."

for batch in "$work"/batch.*; do
  # "12:1,2,3" lines -> {"points": [[1,2,3], ...]}; the line numbers go aside
  cut -d: -f1 "$batch" > "$work/lines"
  cut -d: -f2- "$batch" | tr -d '\r \t' |
    jq -R -s '{points: (split("\n") | map(select(length > 0) | split(",") | map(tonumber)))}' > "$work/request.json"
  status=$(post "/v1/geometries/$id/project" "$work/request.json")
  code=$(jq -r '.error.code // empty' "$work/response.json")
  if { [ "$status" = 404 ] && [ "$code" = geometry_not_found ]; } ||
     { [ "$status" = 503 ] && [ "$code" = registry_unavailable ]; }; then
    jq --slurpfile geometry "$geometry_file" '{geometry: $geometry[0]} + .' "$work/request.json" > "$work/oneshot.json"
    status=$(post /v1/project "$work/oneshot.json")
  fi
  [ "$status" = 200 ] || fail "a batch was refused" "$status"
  # A point without a finite answer has empty foot point, distance and parameters.
  jq -r --argjson dim "$dim" --argjson params "$params" '.results[]
         | [(.foot_point // [range($dim) | null])[], .distance, .diagnostics.status]
           + (if $params > 0 then (.parameters // [range($params) | null]) else [] end)
         | map(if . == null then "" else tostring end) | join(",")' "$work/response.json" |
    paste -d, "$work/lines" -
done
