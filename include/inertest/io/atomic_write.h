// Files that inertest writes appear whole or not at all: the content goes to a temporary file in
// the same directory, is flushed to disk, then renamed over the target.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace inertest {

// Throws Error naming the path when the file cannot be written.
void write_file_atomically(const std::string& path, std::string_view content);

// The last step of writing a set of files whole or none: moves each of `names` (relative paths)
// from `staging` to the same place under `out`, once none of those places is found to be a
// directory (an Error naming the first, nothing moved: a rename onto it failed half-way through).
void move_staged_files(const std::filesystem::path& staging, const std::filesystem::path& out,
                       const std::vector<std::filesystem::path>& names);

// An Error naming `out` when it exists and is not a directory (creating it, and any file in it,
// failed with an internal error).
void require_output_directory(const std::filesystem::path& out);

}  // namespace inertest
