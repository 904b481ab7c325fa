// The demo's report as a lab would sign it: the plan's navigation-grade specification gives a
// verdict per limit, PASS and FAIL both, each agreeing with the simulated gyro's truth; and no
// output names a paper by a file name.
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "inertest/core/units.h"
#include "test_util/demo_campaign.h"

namespace inertest {
namespace {

using testing::read_file;

TEST(Demo, ReportShowsPassAndFailPerLimitAsTheTruthDecides) {
  const std::string& out = testing::demo_campaign_directory();
  const auto results = nlohmann::json::parse(read_file(out + "/results.json"));
  const auto truth = nlohmann::json::parse(read_file(out + "/lab/truth.json"));

  // The true value of every figure the simulator knows, by procedure and figure.
  std::map<std::pair<std::string, std::string>, nlohmann::json> true_values;
  for (const auto& t : truth.at("truth")) {
    if (!t.at("figure").is_null()) true_values[{t.at("procedure"), t.at("figure")}] = t;
  }
  std::size_t passed = 0;
  std::size_t failed = 0;
  std::size_t judged_by_truth = 0;
  for (const auto& v : results.at("verdicts")) {
    const bool pass = v.at("pass").get<bool>();
    (pass ? passed : failed) += 1;
    const auto found = true_values.find({v.at("procedure"), v.at("figure")});
    if (found == true_values.end()) continue;
    // The verdict the true value would get (expected = true value + the rig's known systematic).
    const double expected = convert(found->second.at("expected").get<double>(), found->second.at("unit").get<std::string>(),
                                    v.at("unit").get<std::string>());
    const bool true_pass = (!v.contains("min") || expected >= v.at("min").get<double>()) &&
                           (!v.contains("max") || expected <= v.at("max").get<double>());
    EXPECT_EQ(pass, true_pass) << v.dump() << " truth " << found->second.dump();
    ++judged_by_truth;
  }
  EXPECT_GE(passed, 15u);
  EXPECT_EQ(failed, 2u);
  EXPECT_GE(judged_by_truth, 15u);
  EXPECT_EQ(results.at("verdict"), "FAIL");

  const std::string report = read_file(out + "/report.txt");
  EXPECT_NE(report.find("Specification limits"), std::string::npos);
  EXPECT_NE(report.find("  FAIL  scale_factor_temperature / Sensitivity Kt = 1.49"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("  FAIL  bias_repeatability / Bias repeatability Br = "), std::string::npos);
  // A row of a table named by its place, as the HTML report's compliance table names it.
  EXPECT_NE(report.find("  PASS  bias_static / Bias stability (100 s) = "), std::string::npos);
  // The procedure's own yes/no judged against its specification, not "1 (>= 1)".
  EXPECT_NE(report.find("  PASS  polarity / As specified = yes (yes)"), std::string::npos);
  EXPECT_NE(report.find("Verdict: FAIL"), std::string::npos);
  const std::string html = read_file(out + "/report.html");
  EXPECT_NE(html.find("verdict-cell pass\">PASS<"), std::string::npos);
  EXPECT_NE(html.find("verdict-cell fail\">FAIL<"), std::string::npos);
  EXPECT_EQ(html.find("No specification limits"), std::string::npos);

  for (const auto& entry : std::filesystem::recursive_directory_iterator(out)) {
    if (!entry.is_regular_file()) continue;
    const auto extension = entry.path().extension();
    if (extension != ".json" && extension != ".txt" && extension != ".html" && extension != ".toml") continue;
    EXPECT_FALSE(testing::names_a_seed_file(read_file(entry.path().string()))) << entry.path();
  }
}

}  // namespace
}  // namespace inertest
