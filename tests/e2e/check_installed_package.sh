#!/usr/bin/env bash
# The core as an installed C++ library: installs the build's `development` component (headers,
# the layers' static libraries, the CMake package) into an empty temporary prefix, configures and
# builds examples/cpp against it with find_package(footpoint), outside this tree's build, runs the
# example and checks its answers (exact foot points of a torus and a circle, the unknown-method
# error value).
#   tests/e2e/check_installed_package.sh BUILD_DIR SOURCE_DIR [FLAGS]
# FLAGS are compile and link flags the example needs to link the installed libraries (a sanitizer
# build's instrumentation).
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 BUILD_DIR SOURCE_DIR [FLAGS]" >&2
  exit 2
fi
flags=${3:-}
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
tmp=$(mktemp -d /tmp/footpoint-package.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

cmake --install "$build" --prefix "$tmp/prefix" --component development > "$tmp/install.log" ||
  { cat "$tmp/install.log"; fail "cmake --install --component development"; }
[ -f "$tmp/prefix/lib/cmake/footpoint/footpointConfig.cmake" ] || fail "no footpointConfig.cmake installed"
[ -f "$tmp/prefix/include/footpoint/footpoint.hpp" ] || fail "the public header footpoint.hpp is not installed"
[ -f "$tmp/prefix/include/footpoint/compiled/compiled_geometry.hpp" ] || fail "the public headers are not installed"
# internal headers stay in the source tree: a solver's, a seeding structure's
for internal in parametric/solvers/surface_certificate.hpp parametric/seeding/surface_cells.hpp \
  implicit/solvers/implicit_curve_auto.hpp compiled/parametric_surface_geometry.hpp; do
  [ ! -e "$tmp/prefix/include/footpoint/$internal" ] || fail "the internal header $internal is installed"
done
[ ! -e "$tmp/prefix/bin" ] || fail "the development component installs the server too"
echo "ok: installed $(find "$tmp/prefix" -type f | wc -l) files into a temporary prefix"

cmake -S "$source_dir/examples/cpp" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
  > "$tmp/configure.log" 2>&1 || { cat "$tmp/configure.log"; fail "configure examples/cpp"; }
cmake --build "$tmp/build" > "$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; fail "build examples/cpp"; }
echo "ok: examples/cpp configured and built against the installed package"

out=$("$tmp/build/project_in_process") || fail "the example exited with an error"
echo "$out"
/usr/bin/python3 - "$out" <<'PY' || fail "the example's answers"
import re, sys
lines = sys.argv[1].splitlines()
expected = [("surface auto", (2.5, 0.0, 0.0), 0.5), ("curve newton", (1.0, 0.0, 0.0), 1.0),
            ("curve newton", (0.0, 1.0, 0.0), 0.5)]
for line, (what, foot, distance) in zip(lines, expected):
    m = re.fullmatch(r"(.+): foot (\S+) (\S+) (\S+), distance (\S+), (\w+)", line)
    assert m and m.group(1) == what and m.group(6) == "converged", line
    assert all(abs(float(m.group(2 + k)) - foot[k]) <= 1e-15 for k in range(3)), line
    assert abs(float(m.group(5)) - distance) <= 1e-15, line
assert lines[3] == "unknown method 'gsa' for a parametric_curve (auto, newton, curvature_circle)", lines[3]
assert len(lines) == 4
PY
echo "ok: the example's foot points and its unknown-method error are the expected ones"
