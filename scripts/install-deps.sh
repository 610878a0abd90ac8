#!/usr/bin/env bash
# Installs everything footpoint needs to build, test and benchmark, from Debian 12 packages.
# Idempotent; run as root (or with sudo available). Used by both README commands and by CI.
# Packages given as arguments are installed as well (fuzz/install.sh adds clang's libFuzzer).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
packages=(
  build-essential cmake pkg-config git
  libcpp-httplib-dev nlohmann-json3-dev libmuparser-dev libspdlog-dev doctest-dev  # design card
  libnanoflann-dev   # k-d tree over cached samples (auto methods' seeding)
  libhiredis-dev     # build list: the shared geometry registry's Redis client (run time: libhiredis0.14)
  redis-server       # test list: the registry tests start their own Redis on loopback
  libjs-three        # build list: three.js and its orbit controls, embedded in the server for the pages (ui/)
  libbenchmark-dev   # bench/
  python3 python3-yaml python3-jsonschema   # openapi / manifest checks in the tests
  python3-numpy python3-scipy python3-sympy python3-mpmath  # shared/cases/oracle.py, reference generators
  curl jq wrk
  chromium python3-websocket   # test list: the browser pages in headless chromium (tests/ui_playground_browser.py)
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
