#!/usr/bin/env bash
# Fails when a tracked file names a path outside the repository: the parent folder's shared
# material or an absolute path into the development machine's work tree. A clone of the repository
# alone must build, test and benchmark; nothing may read or point at what lies beside it.
#   bash scripts/check_paths.sh              every file git tracks (or, outside a git checkout,
#                                            every file but build directories)
#   bash scripts/check_paths.sh FILE...      those files
#   bash scripts/check_paths.sh --self-test  a planted path must be caught, a clean file must pass
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

# Written in pieces, so that this file does not match itself.
s="shared"
w="work"
patterns=("\.\./$s" "$s/cases" "$s/peers" "$s/papers" "/$w/")

scan() {  # scan FILE...: prints each match as file:line: text, returns 1 if there is one
  local args=()
  for p in "${patterns[@]}"; do args+=(-e "$p"); done
  if grep -I -n -H "${args[@]}" -- "$@"; then return 1; fi
  return 0
}

if [ "${1:-}" = "--self-test" ]; then
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  printf 'a clean line\nsee tests/data/papers/README.md\n' >"$tmp/clean.txt"
  scan "$tmp/clean.txt" >/dev/null || { echo "check_paths self-test: a clean file was flagged" >&2; exit 1; }
  for planted in "../$s/cases/public_cases.json" "$s/peers/surfaces.txt" "/$w/main/README.md" \
    "cp -r ../$s/papers/x ."; do
    printf 'line one\nread %s here\n' "$planted" >"$tmp/planted.txt"
    if scan "$tmp/planted.txt" >/dev/null; then
      echo "check_paths self-test: '$planted' was not caught" >&2
      exit 1
    fi
  done
  echo "check_paths self-test: ${#patterns[@]} patterns, planted paths caught, a clean file passes"
  set -- # and then check the repository itself
fi

cd "$root"
if [ $# -gt 0 ]; then
  files=("$@")
elif git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git -C "$root" ls-files)
else
  mapfile -t files < <(find . -type f -not -path './.git/*' -not -path './build*' | sed 's|^\./||')
fi
present=()
for f in "${files[@]}"; do [ -f "$f" ] && present+=("$f"); done
if scan "${present[@]}"; then
  echo "check_paths: ${#present[@]} files, no path outside the repository"
else
  echo "check_paths: the lines above name paths outside the repository" >&2
  exit 1
fi
