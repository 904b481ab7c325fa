// Files that inertest writes appear whole or not at all: the content goes to a temporary file in
// the same directory, is flushed to disk, then renamed over the target.
#pragma once

#include <string>
#include <string_view>

namespace inertest {

// Throws Error naming the path when the file cannot be written.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace inertest
