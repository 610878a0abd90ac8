#!/usr/bin/env bash
# Runs clang-tidy with the checks of .clang-tidy (every warning an error) on the C++ sources of a
# configured build directory whose paths match REGEX, two at a time. The header filter of
# .clang-tidy reports the headers of server/, tests/, bench/ and fuzz/ as well; core/ is left out.
#   bash scripts/check_tidy.sh BUILD_DIR [REGEX]     (default REGEX: '/(server|tests|bench|fuzz)/')
# BUILD_DIR needs compile_commands.json (every configure writes it: CMAKE_EXPORT_COMPILE_COMMANDS);
# the fuzz targets' sources are in the fuzz build's (fuzz/run.sh).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(realpath "${1:?usage: check_tidy.sh BUILD_DIR [REGEX]}")"
regex="${2:-/(server|tests|bench|fuzz)/}"
[ -f "$build/compile_commands.json" ] || { echo "check_tidy: no $build/compile_commands.json (configure first)" >&2; exit 2; }
command -v run-clang-tidy >/dev/null || { echo "check_tidy: clang-tidy is not installed (scripts/install-deps.sh --test)" >&2; exit 2; }
# Only the tree's own sources: not the files the build generates.
mapfile -t files < <(/usr/bin/python3 - "$build/compile_commands.json" "$root" "$regex" <<'PY'
import json, re, sys
db, root, regex = sys.argv[1], sys.argv[2], re.compile(sys.argv[3])
for entry in json.load(open(db)):
    f = entry['file']
    if f.startswith(root + '/') and regex.search(f[len(root):]):
        print(f)
PY
)
[ ${#files[@]} -gt 0 ] || { echo "check_tidy: no source of $build matches $regex" >&2; exit 2; }
start=$(date +%s)
run-clang-tidy -quiet -p "$build" -j 2 "${files[@]}" >"$build/clang-tidy.log" 2>&1 || status=$?
# run-clang-tidy prints each file's command and its warnings; only the diagnostics matter here
sed 's/\x1b\[[0-9;]*m//g' "$build/clang-tidy.log" | grep -E "(warning|error): " | sort -u || true
if [ "${status:-0}" -ne 0 ]; then
  echo "check_tidy: clang-tidy reports the lines above ($build/clang-tidy.log)" >&2
  exit 1
fi
echo "check_tidy: ${#files[@]} files clean in $(( $(date +%s) - start )) s ($(clang-tidy --version | grep -o 'version [0-9.]*'))"
