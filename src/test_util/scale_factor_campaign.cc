#include "test_util/scale_factor_campaign.h"

namespace inertest::testing {

nlohmann::json scale_factor_campaign(const std::string& instrument, const std::string& tested_on, double scale_factor) {
  const bool pass = scale_factor >= 35999.0 && scale_factor <= 36001.0;
  return {{"results_schema_version", 1},
          {"inertest_version", "0.1.0"},
          {"tested_on", tested_on},
          {"processed_at", tested_on + "T12:00:00Z"},
          {"plan", {{"title", "acceptance " + instrument}}},
          {"instrument", {{"id", instrument}, {"type", "gyro"}}},
          {"site", nlohmann::json::object()},
          {"procedures",
           {{{"name", "scale_factor"},
             {"kind", "scale_factor"},
             {"result", {{"scale_factor", {{"value", scale_factor}, {"unit", "pulse/s/(deg/s)"}, {"uncertainty", 0.03}}}}}}}},
          {"verdicts",
           {{{"procedure", "scale_factor"}, {"figure", "scale_factor"}, {"value", scale_factor},
             {"unit", "pulse/s/(deg/s)"}, {"pass", pass}, {"min", 35999.0}, {"max", 36001.0}}}},
          {"verdict", pass ? "PASS" : "FAIL"}};
}

}  // namespace inertest::testing
