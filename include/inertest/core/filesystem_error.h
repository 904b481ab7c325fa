// A path the system refuses (a read-only directory, a file where a directory is to be made) is bad
// input, not an internal error: the command line and Python say it as an Error at the path.
#pragma once

#include <filesystem>

#include "inertest/core/error.h"

namespace inertest {

// The Error of a std::filesystem failure: at its first path, with the system's reason and, where
// the failure names two (a rename), the other path.
Error error_of(const std::filesystem::filesystem_error& failure);

}  // namespace inertest
