// Reading UTF-8 text one code point at a time (instrument ids, hand-check names).
#pragma once

#include <cstddef>
#include <string_view>

namespace inertest {

// The code point of the UTF-8 sequence at `at` and its length in bytes (`size`); U+FFFD with a size
// of 1 for a sequence cut short by the end of the text.
char32_t code_point_at(std::string_view text, std::size_t at, std::size_t& size);

// Punctuation and blanks beyond ASCII: a no-break space, general punctuation (U+2000-U+206F: Unicode
// spaces, dashes, zero-width characters), CJK symbols and punctuation (、。「」), and full-width
// punctuation (（）：，).
bool is_unicode_punctuation_or_blank(char32_t c);

}  // namespace inertest
