// A reported figure: a value with its unit and, where known, its 1-sigma uncertainty.
// Serialises to {"value": v, "unit": "u"} plus "uncertainty" when known.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace inertest {

struct Figure {
  double value = 0.0;
  std::string unit = "1";
  std::optional<double> uncertainty;  // 1 sigma, in the same unit

  // The same figure expressed in another unit of the same dimension (uncertainty too).
  Figure in(const std::string& other_unit) const;
};

void to_json(nlohmann::json& json, const Figure& figure);
void from_json(const nlohmann::json& json, Figure& figure);

}  // namespace inertest
