// The files of the browser pages (ui/: the playground at /, the API reference at /docs, their
// scripts and styles; three.js and its orbit controls from Debian's libjs-three), embedded at
// build time (server/CMakeLists.txt generates their .cpp) and served under /ui/{name}.
#pragma once
#include <string_view>
#include <vector>

namespace footpoint::server {

struct UiFile {
  std::string_view name;          // "playground.js"
  std::string_view content_type;  // "text/javascript; charset=utf-8"
  std::string_view text;
};

const std::vector<UiFile>& ui_files();

}  // namespace footpoint::server
