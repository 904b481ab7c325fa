// Plan kind "hand_checks": GJB 2426A-2004 5.2-5.4, values measured by hand.
//   [[procedure.check]]
//   name = "Insulation resistance"   # the result key is its snake_case: insulation_resistance
//   value = 120.0                    # a number, or for appearance (5.2) "pass" / "fail"
//   unit = "MOhm"                    # optional, default "1"
//   min = 20.0                       # optional limits, verdicts of the campaign as [procedure.limits]
//   max = 1000.0
#include <map>
#include <span>

#include "campaign/step_registry.h"
#include "inertest/procedures/hand_checks.h"

namespace inertest::campaign {

PreparedAction prepare_hand_checks_step(PlanTable& step, const PlanContext&) {
  std::vector<HandCheck> checks;
  std::vector<FieldSpec> figures;  // one per check: what [procedure.limits] may name
  std::map<std::string, SourceLocation> keys;  // each check's result key, where it is named
  std::vector<StatedLimit> limits;             // each check's min, max or pass/fail
  for (auto& table : step.tables("check")) {
    HandCheck check;
    check.name = table.string("name");
    const toml::node* value = table.raw().get("value");
    if (value != nullptr && value->is_string()) {
      const std::string verdict = *table.optional_string("value");
      if (verdict != "pass" && verdict != "fail") table.fail_at("value", "must be a number, \"pass\" or \"fail\"");
      check.verdict = verdict == "pass";
    } else {
      check.value = table.number("value");
    }
    check.unit = table.string_or("unit", "1");
    check.min = table.optional_number("min");
    check.max = table.optional_number("max");
    table.require_all_used();
    // Each check on its own, so that an error names its table (two of one key: the second's name).
    try {
      hand_checks(std::span(&check, 1));
    } catch (const Error& e) {
      table.fail(e.message());
    }
    const auto [first, inserted] = keys.emplace(snake_case_key(check.name), table.location_of_key("name"));
    if (!inserted) {
      table.fail_at("name", "'" + check.name + "' has the result key '" + first->first + "' of the check at " +
                                first->second.to_string() + ": give each check a name of its own");
    }
    // The check's own bounds, and a pass/fail check's "pass" (its figure 1), judged as plan limits.
    if (check.min || check.max || check.verdict) {
      limits.push_back({first->first, check.verdict ? std::optional(1.0) : check.min, check.max,
                        table.location_of_key(check.verdict ? "value" : check.min ? "min" : "max"),
                        check.verdict.has_value()});
    }
    checks.push_back(check);
    figures.push_back({first->first, FieldRole::headline, check.name, "", ""});
    figures.back().value = FieldValue::figure;
    figures.back().unit = check.verdict ? "1" : check.unit;
  }
  if (checks.empty()) step.fail("needs at least one [[procedure.check]] table (name, value, unit, min, max)");
  // The table of every check, which a limit may name by a JSON pointer ("/checks/0/value").
  figures.push_back({"checks", FieldRole::table, "checks", "", ""});
  figures.back().value = FieldValue::rows;
  return {[checks](const StepRunContext&) { return hand_checks(checks).to_json(); }, nlohmann::json::object(), figures,
          limits};
}

}  // namespace inertest::campaign
