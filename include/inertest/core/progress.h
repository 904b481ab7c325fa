// Progress of long work, reported by the library through a callback the caller supplies (the CLI
// prints it on stderr when stderr is a terminal). The library itself never prints.
#pragma once

#include <functional>
#include <string_view>

namespace inertest {

// stage: what is being done; fraction: 0 to 1.
using ProgressCallback = std::function<void(std::string_view stage, double fraction)>;

}  // namespace inertest
