// The viewer's JavaScript (viewer/src, three.js included) bundled by esbuild at build time and
// compiled into the library (viewer/build.mjs writes its definition), so that the `kaboum` tool
// alone writes pages that fetch nothing. Reference: docs/viewer.md.
#pragma once

#include <string_view>

namespace kaboum::web {

std::string_view viewerScript();

}  // namespace kaboum::web
