// The version of footpoint, one for everything that names one: the CMake project's (the
// definition FOOTPOINT_VERSION comes from project(footpoint VERSION ...)), which openapi.yaml's
// info.version, the image's label and tag, `footpoint-server --version`, the start-up log line
// and /metrics' footpoint_build_info repeat (tests/server/operations_test.cpp and
// deploy/check_manifests.py hold them equal).
#pragma once
#include <string_view>

namespace footpoint::server {

inline constexpr std::string_view kVersion = FOOTPOINT_VERSION;

}  // namespace footpoint::server
