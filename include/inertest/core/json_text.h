// The JSON text of a value, as inertest writes it everywhere (stdout, results.json, exports, the
// archive, the web view). Text read from a lab's files is not always UTF-8 (a header exported by a
// Chinese Windows Excel is GBK, a European one Latin-1): each byte that is not part of valid UTF-8
// is written as U+FFFD instead of ending the program (nlohmann::json's own dump throws on it).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace inertest {

// value.dump(indent) with invalid UTF-8 replaced (indent -1: one line).
std::string json_text(const nlohmann::json& value, int indent = -1);

}  // namespace inertest
