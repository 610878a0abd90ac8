#!/usr/bin/env bash
# openapi.yaml through Redocly's linter (@redocly/cli lint, its recommended rules): the version
# pinned by tests/tools/redocly/package-lock.json, installed there with `npm ci` when missing or
# when the lock file changed. Exit 77 (ctest: skipped) when npm is not installed
# (scripts/install-deps.sh --test installs it).
set -euo pipefail
source_dir=${1:?usage: openapi_lint.sh SOURCE_DIR}
tool="$source_dir/tests/tools/redocly"
export REDOCLY_TELEMETRY=off REDOCLY_SUPPRESS_UPDATE_NOTICE=true NO_UPDATE_NOTIFIER=1
if ! cmp -s "$tool/package-lock.json" "$tool/node_modules/.footpoint-lock" 2>/dev/null; then
  if ! command -v npm >/dev/null; then
    echo "openapi_lint: npm is not installed (scripts/install-deps.sh --test): skipped"
    exit 77
  fi
  (cd "$tool" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$tool/package-lock.json" "$tool/node_modules/.footpoint-lock"
fi
"$tool/node_modules/.bin/redocly" lint --extends=recommended --format=summary "$source_dir/openapi.yaml"
