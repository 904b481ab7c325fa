#include "inertest/core/json_text.h"

#include <gtest/gtest.h>

namespace inertest {
namespace {

// A column named 角速率 in GBK (a Chinese Excel export): every JSON writer ended the program with
// "invalid UTF-8 byte at index 0: 0xBD" (exit 3).
TEST(JsonText, TextThatIsNotUtf8IsWrittenWithReplacementCharacters) {
  const nlohmann::json value = {{"name", "\xbd\xc7\xcb\xd9\xc2\xca"}, {"unit", "\xb0" "C"}, {"ok", "角速率"}};
  const std::string text = json_text(value);
  EXPECT_EQ(nlohmann::json::parse(text),
            (nlohmann::json{{"name", "\uFFFD\uFFFD\uFFFD\uFFFD\uFFFD\uFFFD"}, {"unit", "\uFFFDC"}, {"ok", "角速率"}}));
  EXPECT_EQ(json_text({{"a", 1}}, 2), "{\n  \"a\": 1\n}");
}

}  // namespace
}  // namespace inertest
