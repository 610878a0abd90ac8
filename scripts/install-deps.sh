#!/usr/bin/env bash
# Installs footpoint's dependencies from Debian 12 packages. Idempotent; run as root (or with sudo).
#   bash scripts/install-deps.sh            what building and running the service needs
#   bash scripts/install-deps.sh --test     that, and what the tests and benchmarks need
# Further arguments are package names installed as well (fuzz/install.sh adds clang's libFuzzer).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
# Building and running the service (the Dockerfile's build stage installs the same list).
packages=(
  build-essential cmake pkg-config
  libcpp-httplib-dev nlohmann-json3-dev libmuparser-dev libspdlog-dev
  libnanoflann-dev   # k-d tree over cached samples (auto methods' seeding)
  libhiredis-dev     # the shared geometry registry's Redis client (run time: libhiredis0.14)
  libssl-dev         # HTTPS (cpp-httplib's SSLServer), API keys' SHA-256 (run time: libssl3)
  libjs-three        # three.js and its orbit controls, embedded in the server for the pages (ui/)
)
# The test suite, the benchmarks and the checks CI runs.
test_packages=(
  git                                        # ctest's clone test, CI's clean clone
  doctest-dev                                # tests/
  redis-server                               # the registry tests start their own Redis on loopback
  python3 python3-yaml python3-jsonschema    # openapi / manifest checks in the tests
  python3-numpy python3-scipy python3-sympy python3-mpmath  # tests/tools/ reference generators
  curl jq                                    # deploy checks, examples/project_csv.sh
  openssl                                    # the TLS tests make their certificate at test time
  wrk                                        # bench/http_bench.sh
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev  # bench/occt/
  libocct-data-exchange-dev                  # tools/step_import/ (footpoint-import reads STEP)
  clang-format clang-tidy shellcheck         # scripts/check_format.sh, scripts/check_tidy.sh, deploy_shellcheck
  chromium python3-websocket                 # the browser pages in headless chromium (tests/e2e/ui_playground_browser.py)
  python3-matplotlib                         # examples/inspection/: the deviation colour map and histogram
  nodejs                                     # tests/e2e/client_js_test.mjs: the JavaScript client (ui/footpoint-client.js)
)
# npm (with Node.js): the build installs Swagger UI for /docs with it (npm ci against
# ui/vendor/package-lock.json; server/CMakeLists.txt), and tests/e2e/openapi_lint.sh Redocly's linter
# (tests/tools/redocly/package-lock.json). Debian's, unless an npm is already there (e.g. with
# another Node.js distribution).
command -v npm >/dev/null || packages+=(npm)
extra=()
for arg in "$@"; do
  if [ "$arg" = "--test" ]; then packages+=("${test_packages[@]}"); else extra+=("$arg"); fi
done
packages+=("${extra[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
