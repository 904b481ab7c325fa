// Checks measured by hand: GJB 2426A-2004 5.2 (appearance), 5.3.1 (insulation resistance, by a
// megohmmeter at 100 V), 5.3.2 (impedance), 5.3.3 (dielectric strength), 5.4 (power per supply).
// The plan records each measured value with its limits; each becomes a Figure and a pass flag so
// that these checks enter the results and the report like every other figure.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "inertest/core/figure.h"

namespace inertest {

struct HandCheck {
  std::string name;             // e.g. "Insulation resistance, case to power"
  // A measured value, or for a check judged by eye (appearance, 5.2) the verdict "pass" / "fail".
  std::optional<double> value;
  std::optional<bool> verdict;  // the "pass" / "fail" verdict when there is no value
  std::string unit = "1";
  std::optional<double> min;
  std::optional<double> max;  // alone, it bounds the magnitude (as a plan's limit): |value| <= max
};

struct HandCheckResult {
  std::string key;   // snake_case of the name, the key of the figure in the JSON
  HandCheck check;
  Figure figure;     // the value in its unit; a verdict is 1 (pass) or 0 (fail) with unit "1"
  bool pass = true;
};

struct HandChecksResult {
  std::vector<HandCheckResult> checks;
  bool all_pass = true;

  // {"<key>": Figure, ..., "check_pass": {"<key>": bool}, "checks": [...], "all_pass": bool}
  nlohmann::json to_json() const;
  std::string report() const;
};

// snake_case key of a check's name: lower-case letters and digits, letters of other scripts as
// they are, runs of anything else become one '_' ("Power, +15 V supply" -> "power_15_v_supply",
// "绝缘电阻 (壳体)" -> "绝缘电阻_壳体").
std::string snake_case_key(const std::string& name);

// Throws Error for no checks, an empty name, two names with the same key, a check with both or
// neither of value and verdict, a verdict with limits, min > max, or a non-finite number.
HandChecksResult hand_checks(std::span<const HandCheck> checks);

}  // namespace inertest
