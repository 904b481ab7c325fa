#include "campaign/step_registry.h"

#include <map>

namespace inertest::campaign {
namespace {

std::map<std::string, StepPreparer>& steps() {
  static std::map<std::string, StepPreparer> registry;
  return registry;
}

}  // namespace

bool register_step(const std::string& kind, StepPreparer preparer) {
  steps().emplace(kind, std::move(preparer));
  return true;
}

const StepPreparer* find_step(const std::string& kind) {
  const auto it = steps().find(kind);
  return it == steps().end() ? nullptr : &it->second;
}

std::vector<std::string> registered_step_kinds() {
  std::vector<std::string> kinds;
  for (const auto& [kind, preparer] : steps()) kinds.push_back(kind);
  return kinds;
}

double scale_factor_or_nominal(PlanTable& step, const PlanContext& context, const std::string& input_unit) {
  if (const auto given = step.optional_number("scale_factor")) return *given;
  if (context.instrument.nominal_scale_factor) return *context.instrument.nominal_scale_factor;
  step.fail("needs scale_factor (output units per " + input_unit + ") or [instrument] nominal_scale_factor");
}

nlohmann::json Instrument::to_json() const {
  nlohmann::json json = {{"id", id}, {"type", type}, {"output_unit", output_unit}};
  if (nominal_scale_factor) json["nominal_scale_factor"] = *nominal_scale_factor;
  if (sample_rate_hz) json["sample_rate_hz"] = *sample_rate_hz;
  return json;
}

nlohmann::json Site::to_json() const {
  return {{"name", name}, {"latitude_deg", latitude_deg}, {"gravity_m_s2", gravity_m_s2}, {"heading_deg", heading_deg}};
}

}  // namespace inertest::campaign
