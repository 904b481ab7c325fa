#include "inertest/version.h"

namespace inertest {

std::string version() { return INERTEST_VERSION; }

}  // namespace inertest
