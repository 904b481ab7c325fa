#include "campaign/step_registry.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>

#include "campaign/procedure_step.h"

namespace inertest::campaign {
namespace {

// The plan kinds that are not declared procedures.
const std::map<std::string, StepPreparer>& special_steps() {
  static const std::map<std::string, StepPreparer> special = {{"hand_checks", prepare_hand_checks_step}};
  return special;
}

// The declared procedures' steps (core/procedure_spec.h), built on first use.
const std::map<std::string, StepPreparer>& declared_steps() {
  static const std::map<std::string, StepPreparer> declared = [] {
    std::map<std::string, StepPreparer> made;
    for (const ProcedureSpec& spec : procedure_specs()) {
      made.emplace(spec.kind, [&spec](PlanTable& step, const PlanContext& context) {
        return prepare_procedure_step(spec, step, context);
      });
    }
    return made;
  }();
  return declared;
}

// The special steps, then the declared procedures'.
std::array<const std::map<std::string, StepPreparer>*, 2> all_steps() { return {&special_steps(), &declared_steps()}; }

}  // namespace

const StepPreparer* find_step(const std::string& kind) {
  for (const auto* registry : all_steps()) {
    const auto it = registry->find(kind);
    if (it != registry->end()) return &it->second;
  }
  return nullptr;
}

std::vector<std::string> registered_step_kinds() {
  std::vector<std::string> kinds;
  for (const auto* registry : all_steps()) {
    for (const auto& [kind, preparer] : *registry) kinds.push_back(kind);
  }
  std::sort(kinds.begin(), kinds.end());
  return kinds;
}

std::optional<std::string> OutputClaims::claim(const std::string& path, const SourceLocation& where) {
  const std::string normal = std::filesystem::path(path).lexically_normal().string();
  if (normal == "results.json" || normal == "report.html") return "which the run writes itself";
  const auto [earlier, claimed] = claims_.emplace(normal, where);
  if (claimed) return std::nullopt;
  return "which the procedure at " + earlier->second.to_string() + " writes too";
}

nlohmann::json Instrument::to_json() const {
  nlohmann::json json = {{"id", id}, {"type", type}, {"output_unit", output_unit}};
  if (nominal_scale_factor) json["nominal_scale_factor"] = *nominal_scale_factor;
  if (sample_rate_hz) json["sample_rate_hz"] = *sample_rate_hz;
  return json;
}

nlohmann::json Site::to_json() const {
  nlohmann::json json = {{"name", name}, {"gravity_m_s2", gravity_m_s2}, {"heading_deg", heading_deg}};
  if (latitude_deg) json["latitude_deg"] = *latitude_deg;
  return json;
}

}  // namespace inertest::campaign
