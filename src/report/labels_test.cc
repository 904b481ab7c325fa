#include "report/labels.h"

#include <set>

#include "test_util/test_util.h"

namespace inertest::report {
namespace {

TEST(ReportLabels, EveryKeyIsUniqueAndTranslated) {
  std::set<std::string_view> seen;
  const Labels english(Language::english);
  const Labels chinese(Language::chinese);
  for (const auto key : Labels::keys()) {
    EXPECT_TRUE(seen.insert(key).second) << "duplicate key " << key;
    EXPECT_FALSE(english(key).empty()) << key;
    EXPECT_FALSE(chinese(key).empty()) << key;
  }
}

TEST(ReportLabels, GjbTermsInChinese) {
  const Labels chinese(Language::chinese);
  EXPECT_EQ(chinese("scale_factor"), "标度因数");
  EXPECT_EQ(chinese("nonlinearity"), "标度因数非线性度");
  EXPECT_EQ(chinese("bias_stability"), "零偏稳定性");
  EXPECT_EQ(chinese("random_walk_coefficient"), "随机游走系数");
  EXPECT_EQ(chinese("bandwidth"), "带宽");
  EXPECT_EQ(chinese.title_of("bandwidth"), "频带宽度与输出延迟时间");
  EXPECT_EQ(Labels(Language::english)("bias_stability"), "Bias stability");
}

TEST(ReportLabels, UnknownKeysReadAsThemselves) {
  EXPECT_EQ(Labels(Language::english)("some_new_figure"), "Some new figure");
  EXPECT_EQ(Labels(Language::chinese)("kind.some_new_kind"), "Some new kind");
  EXPECT_FALSE(Labels::known("some_new_figure"));
  EXPECT_EQ(humanise_key("ui.x_y"), "X y");
}

TEST(ReportLabels, TableOrderRanksFiguresAndUnknownKeysLast) {
  EXPECT_LT(Labels::rank("scale_factor"), Labels::rank("nonlinearity"));
  EXPECT_LT(Labels::rank("static_output_start"), Labels::rank("static_output_end"));
  EXPECT_EQ(Labels::rank("unknown_key"), Labels::keys().size());
}

}  // namespace
}  // namespace inertest::report
