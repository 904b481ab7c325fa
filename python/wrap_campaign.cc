// campaign: TOML test plans that run every procedure on its data files and check the limits
// (IEEE Std 952-1997 specification format), as `inertest run`.
#include "bindings.h"
#include "inertest/campaign/campaign.h"
#include "inertest/report/report.h"

namespace inertest::python {
namespace {

struct CampaignTag {};

}  // namespace

void wrap_campaign(py::module_& module) {
  using namespace pybind11::literals;
  module.def("plan_kinds", &plan_kinds, "Every procedure kind a test plan may name, sorted.");
  module.def(
      "validate_plan", [](const std::filesystem::path& plan_path) { return to_plain_python(validate_plan(plan_path.string())); },
      "plan_path"_a,
      "Loads and validates a test plan without running it; returns the validated plan as a dict. Raises\n"
      "inertest.Error naming the plan file and line.");
  py::class_<ResultOf<CampaignTag>, Result>(
      module, "CampaignResult",
      "A test campaign's results: members as in results.json (every procedure's figures and every limit's\n"
      "verdict); report() is the readable summary.");
  module.def(
      "run_campaign",
      [](const std::filesystem::path& plan_path, const std::filesystem::path& out_dir) {
        CampaignSummary summary;
        {
          py::gil_scoped_release release;
          summary = run_campaign(plan_path.string(), out_dir.string());
        }
        return ResultOf<CampaignTag>(summary.results, report::render_text_report(summary.results, {}));
      },
      "plan_path"_a, "out_dir"_a,
      "Runs a test plan as `inertest run`: validates the whole plan first (nothing runs on an error), runs\n"
      "every procedure, checks the limits and writes out_dir/results.json. Every procedure of the library\n"
      "is reachable this way, including those without a function of their own here.");
}

}  // namespace inertest::python
