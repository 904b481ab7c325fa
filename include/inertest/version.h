#pragma once

#include <string>

namespace inertest {

// The library's version, "MAJOR.MINOR.PATCH".
std::string version();

}  // namespace inertest
