// The web view's interactive plots: the script src/serve/assets/plots.js, compiled in by CMake
// (cmake/plot_script.cc.in), so the server needs no file and no network to serve it.
#pragma once

#include <string_view>

namespace inertest::serve {

// The text of src/serve/assets/plots.js.
std::string_view plot_script();

}  // namespace inertest::serve
