#include "report/labels.h"

#include "inertest/core/procedure_spec.h"

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

// The members of every declared curve that the generic plot labels (procedure_plots.cc) read in
// Chinese in a Chinese report: none falls back to the English of humanise_key.
TEST(ReportLabels, EveryDeclaredCurveMemberHasAChineseLabel) {
  const Labels chinese(Language::chinese);
  for (const ProcedureSpec& spec : procedure_specs()) {
    for (const FieldSpec& field : spec.fields) {
      if (field.role != FieldRole::curve) continue;
      for (const std::string& member : field.axes) {
        EXPECT_NE(chinese(member), humanise_key(member)) << spec.kind << " " << field.name << " " << member;
      }
    }
  }
  EXPECT_EQ(chinese("time"), "时间");  // the axis quantity of that name
  EXPECT_EQ(chinese("heating"), "升温");
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
