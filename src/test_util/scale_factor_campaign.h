// A small campaign's results for the tests of the archive's readers (inertest serve).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace inertest::testing {

// A results.json of one scale factor test, as inertest run writes it: the figure (uncertainty
// 0.03 pulse/s/(deg/s)), its limit 35999 .. 36001 pulse/s/(deg/s) and the verdict on it.
nlohmann::json scale_factor_campaign(const std::string& instrument, const std::string& tested_on, double scale_factor);

}  // namespace inertest::testing
