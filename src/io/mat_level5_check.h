// A check of a MAT-file level 5 (v5, v7) before matio reads it: matio allocates what the headers of
// a variable claim (the rank, the names, the fields) before it finds that the file holds less, so a
// corrupt header could make it ask for gigabytes. The check walks the variables' tags as MATLAB's
// "MAT-File Format" (2021, chapter 1) lays them out, within the bytes the file holds.
#pragma once

#include <string>

namespace inertest {

// Throws Error naming the file and the byte offset (in a compressed variable: the variable's offset
// and the offset within its inflated bytes) of a tag that does not fit in its element or the file,
// a rank above 64, a name above 4096 bytes, a struct of more than 65536 fields. Only the headers are
// checked, and of a variable larger than 1 MiB (compressed: inflated) only its first MiB; a file that
// is not level 5 (v7.3) is not checked.
void check_mat_level5_headers(const std::string& path);

}  // namespace inertest
