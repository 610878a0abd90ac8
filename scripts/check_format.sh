#!/usr/bin/env bash
# Fails when a tracked C++ file is not laid out as .clang-format says (clang-format in check mode:
# the differences are printed as warnings). Fix with: clang-format -i FILE...
#   bash scripts/check_format.sh [FILE...]      (default: every *.cpp and *.hpp git tracks)
set -euo pipefail
cd "$(dirname "$0")/.."
formatter="${CLANG_FORMAT:-clang-format}"
command -v "$formatter" >/dev/null || { echo "check_format: $formatter is not installed (scripts/install-deps.sh --test)" >&2; exit 2; }
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files '*.cpp' '*.hpp'); fi
"$formatter" --dry-run --Werror "${files[@]}"
echo "check_format: ${#files[@]} files laid out as .clang-format says ($("$formatter" --version | head -1))"
