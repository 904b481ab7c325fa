#include "inertest/report/archive_pages.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

nlohmann::json history() {
  return {{"instrument", "FOG-0417"},
          {"figures",
           {{{"instrument", "FOG-0417"},
             {"figure", "scale_factor/scale_factor"},
             {"unit", "pulse/s/(deg/s)"},
             {"lower_limit", 35999.0},
             {"upper_limit", 36001.0},
             {"points",
              {{{"tested_on", "2026-02-01"}, {"value", 36000.25}, {"uncertainty", 0.5}, {"campaign", "aaaa"}},
               {{"tested_on", "2026-02-08"}, {"value", 36000.75}, {"uncertainty", nullptr}, {"campaign", "bbbb"}}}}}}}};
}

nlohmann::json fleet() {
  return nlohmann::json::array(
      {{{"figure", "bias/bias"},
        {"unit", "deg/h"},
        {"since", nullptr},
        {"lower_limit", nullptr},
        {"upper_limit", 0.05},
        {"instruments",
         {{{"instrument", "FOG-1"}, {"value", 0.02}, {"uncertainty", nullptr}, {"tested_on", "2026-02-01"}, {"campaign", "c1"}, {"tests", 2}},
          {{"instrument", "FOG-<2>"}, {"value", 0.09}, {"uncertainty", nullptr}, {"tested_on", "2026-02-02"}, {"campaign", "c2"}, {"tests", 1}}}},
        {"control_chart",
         {{"center", 0.055}, {"ucl", 0.24}, {"lcl", -0.13}, {"moving_range_mean", 0.07}, {"sigma", 0.062},
          {"out_of_control", {{{"instrument", "FOG-<2>"}, {"value", 0.09}, {"rule", "beyond_3_sigma"}}}}}},
        {"capability", {{"cp", nullptr}, {"cpk", -0.0268}}}}});
}

TEST(ArchivePages, HistoryShowsEveryPointWithItsUncertaintyAndTheLimits) {
  const std::string page = render_history_page(history(), {Language::english, "2026-03-01"});
  EXPECT_THAT(page, HasSubstr("<h1>FOG-0417</h1>"));
  EXPECT_THAT(page, HasSubstr("<svg"));
  // As the campaign report gives them: to the uncertainty's second digit, in readable units.
  EXPECT_THAT(page, HasSubstr("<td class=\"num\">36000.25 pulse/s/(°/s)</td><td class=\"num\">0.50 pulse/s/(°/s)</td>"));
  // None known: 6 digits, as the report gives such a figure.
  EXPECT_THAT(page, HasSubstr("<td class=\"num\">36000.8 pulse/s/(°/s)</td><td class=\"num\">—</td>"));
  EXPECT_THAT(page, HasSubstr("upper specification limit"));
  EXPECT_THAT(page, HasSubstr("days since first test (2026-02-01)"));
  const std::string zh = render_history_page(history(), {Language::chinese, ""});
  EXPECT_THAT(zh, HasSubstr("仪表历史记录"));
  EXPECT_THAT(zh, HasSubstr("指标上限"));
}

// A row of a table is named by its table and its place ("smoothing_s = 10"), else its number: the
// pages headed the bias stability at 10 s and at 100 s "1" and "2".
TEST(ArchivePages, ARowOfATableIsNamedByItsTableAndPlace) {
  nlohmann::json pages = history();
  nlohmann::json row = pages["figures"][0];
  row["figure"] = "bias_static/bias_stability/1";
  row["unit"] = "deg/h";
  row["place"] = "smoothing_s = 10.0";
  pages["figures"] = nlohmann::json::array({row});  // {row} alone is row itself to clang
  EXPECT_THAT(render_history_page(pages, {Language::english, ""}),
              HasSubstr("Bias stability (smoothing_s = 10.0) (bias_static/bias_stability/1)"));
  pages["figures"][0].erase("place");
  EXPECT_THAT(render_history_page(pages, {Language::english, ""}),
              HasSubstr("Bias stability #2 (bias_static/bias_stability/1)"));
}

TEST(ArchivePages, FleetShowsTheChartTheFlaggedPointAndTheCapability) {
  const std::string page = render_fleet_page(fleet(), {Language::english, ""}, nlohmann::json::array());
  EXPECT_THAT(page, HasSubstr("<svg"));
  EXPECT_THAT(page, HasSubstr("FOG-&lt;2&gt;"));  // escaped
  EXPECT_THAT(page, Not(HasSubstr("FOG-<2>")));
  EXPECT_THAT(page, HasSubstr("beyond 3σ (rule 1)"));
  EXPECT_THAT(page, HasSubstr("<td>-0.0268</td>"));  // Cpk
  EXPECT_THAT(page, HasSubstr("NIST/SEMATECH e-Handbook 6.3.2.2"));
  const std::string zh = render_fleet_page(fleet(), {Language::chinese, ""}, nlohmann::json::array());
  EXPECT_THAT(zh, HasSubstr("超出 3σ 控制限（准则 1）"));
  EXPECT_THAT(zh, HasSubstr("过程能力"));
}

// A test that did not measure the figure (value null) is a row "not measured" and no point; a figure
// no test measured is a table without a plot. The fleet numbers every instrument, measured or not.
TEST(ArchivePages, AFigureNotMeasuredIsSaidAndNotPlotted) {
  nlohmann::json data = history();
  data["figures"][0]["points"][1]["value"] = nullptr;
  const std::string page = render_history_page(data, {Language::english, ""});
  EXPECT_THAT(page, HasSubstr("<td>2026-02-08</td><td class=\"num\">not measured</td>"));
  EXPECT_THAT(page, HasSubstr("<svg"));
  EXPECT_THAT(render_history_page(data, {Language::chinese, ""}), HasSubstr("<td class=\"num\">未测得</td>"));
  data["figures"][0]["points"][0]["value"] = nullptr;
  EXPECT_THAT(render_history_page(data, {Language::english, ""}), Not(HasSubstr("<svg")));

  nlohmann::json unmeasured = fleet();
  unmeasured[0]["instruments"][0]["value"] = nullptr;
  unmeasured[0]["control_chart"] = nullptr;
  const std::string fleet_page = render_fleet_page(unmeasured, {Language::english, ""}, nlohmann::json::array());
  EXPECT_THAT(fleet_page, HasSubstr("<tr><td>1</td><td>FOG-1</td><td>2026-02-01</td><td>not measured</td>"));
  EXPECT_THAT(fleet_page, HasSubstr("<tr><td>2</td><td>FOG-&lt;2&gt;</td><td>2026-02-02</td><td>0.09 °/h</td>"));
  EXPECT_THAT(fleet_page, HasSubstr("<td>bias/bias</td><td>°/h</td><td>1</td>"));  // n: the measured ones
}

// A limit on the magnitude (|value| <= 0.05: the archive gives lower_limit -0.05) draws its -0.05
// only when a value plotted is negative: a positive figure keeps its scale.
TEST(ArchivePages, AMagnitudeLimitDrawsItsLowerLineOnlyUnderANegativeValue) {
  nlohmann::json data = history();
  nlohmann::json& figure = data["figures"][0];
  figure["unit"] = "deg/h";
  figure["lower_limit"] = -0.05;
  figure["upper_limit"] = 0.05;
  figure["limit_on_magnitude"] = true;
  figure["points"][0]["value"] = 0.01;
  figure["points"][1]["value"] = 0.02;
  const std::string positive = render_history_page(data, {Language::english, ""});
  EXPECT_THAT(positive, HasSubstr("upper specification limit"));
  EXPECT_THAT(positive, Not(HasSubstr("lower specification limit")));
  figure["points"][1]["value"] = -0.02;
  EXPECT_THAT(render_history_page(data, {Language::english, ""}), HasSubstr("lower specification limit"));
  figure["limit_on_magnitude"] = false;  // a plan's own min: always drawn
  figure["points"][1]["value"] = 0.02;
  EXPECT_THAT(render_history_page(data, {Language::english, ""}), HasSubstr("lower specification limit"));

  nlohmann::json magnitude = fleet();
  magnitude[0]["lower_limit"] = -0.05;
  magnitude[0]["limit_on_magnitude"] = true;
  EXPECT_THAT(render_fleet_page(magnitude, {Language::english, ""}, nlohmann::json::array()),
              HasSubstr("<td>-0.05 (−max: the max bounds |value|)</td>"));
}

// The pages of an archive: one file per instrument whatever its id, and all of them or none.
TEST(ArchivePages, EveryIdNamesAFileOfItsOwnAndAFailureWritesNothing) {
  EXPECT_EQ(history_page_file_name("FOG-0417"), "history-FOG-0417.html");
  EXPECT_EQ(history_page_file_name("LAB2/FOG-001"), "history-LAB2%2FFOG-001.html");
  EXPECT_EQ(history_page_file_name("50%"), "history-50%25.html");
  EXPECT_EQ(history_page_file_name(".."), "history-...html");
  EXPECT_EQ(history_page_file_name("A B"), "history-A%20B.html");

  testing::ScratchDirectory scratch;
  nlohmann::json data = {{"fleet", fleet()}, {"histories", nlohmann::json::array({history(), history()})}};
  data["histories"][1]["instrument"] = "FOG-0418";
  data["histories"][1]["figures"][0].erase("unit");  // a page that cannot be rendered
  EXPECT_ANY_THROW(write_archive_pages(data, scratch.path() + "/pages", {Language::english, ""}));
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/pages/fleet.html"));
  EXPECT_FALSE(std::filesystem::exists(scratch.path() + "/pages/history-FOG-0417.html"));
  data["histories"][1] = history();
  data["histories"][1]["instrument"] = "LAB2/FOG-001";
  const auto written = write_archive_pages(data, scratch.path() + "/pages", {Language::english, ""});
  EXPECT_EQ(written, (std::vector<std::string>{scratch.path() + "/pages/fleet.html",
                                               scratch.path() + "/pages/history-FOG-0417.html",
                                               scratch.path() + "/pages/history-LAB2%2FFOG-001.html"}));
}

}  // namespace
}  // namespace inertest::report
