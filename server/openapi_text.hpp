// The text of openapi.yaml, embedded at build time (server/CMakeLists.txt generates its .cpp),
// so the installed server serves the description it was built with.
#pragma once
#include <string_view>

namespace footpoint::server {

std::string_view openapi_text();

}  // namespace footpoint::server
