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

// A blank that prints as a space: a space, a no-break space, or another Unicode space (U+1680,
// U+2000-U+200A, U+202F, U+205F, U+3000).
bool is_unicode_blank(char32_t c);

// An ASCII control character (below U+0020, or DEL): no id, name or plan string holds one.
inline bool is_ascii_control(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

// A character that prints as nothing: a zero-width space, non-joiner or joiner, a word joiner, or a
// byte order mark.
bool is_invisible(char32_t c);

}  // namespace inertest
