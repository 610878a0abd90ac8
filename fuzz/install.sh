#!/usr/bin/env bash
# Installs what the fuzz targets need: scripts/install-deps.sh's packages plus Debian's clang 14
# with libFuzzer and the sanitizer runtimes. Idempotent; run as root (or with sudo available).
set -euo pipefail
bash "$(dirname "$0")/../scripts/install-deps.sh" clang-14 libfuzzer-14-dev libclang-rt-14-dev
