#include "inertest/demo/fleet_demo.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <fmt/format.h>

#include "inertest/archive/archive.h"
#include "inertest/campaign/campaign.h"
#include "inertest/core/error.h"
#include "inertest/io/atomic_write.h"
#include "inertest/report/archive_pages.h"
#include "inertest/sim/simulation.h"

namespace inertest {
namespace {

constexpr int instruments = 12;
constexpr const char* test_dates[] = {"2026-03-02", "2026-03-09", "2026-03-16"};

// Nominal scale factor and the specification the processing plan checks (limits on the
// procedures' figures; IEEE Std 952 specification format): K within ±50 ppm, bias at most
// 0.05 deg/h.
constexpr double nominal_scale_factor = 36000.0;
constexpr double scale_factor_tolerance_ppm = 50.0;
constexpr double bias_limit_deg_h = 0.05;

// An instrument of the batch: its true scale factor offset (ppm) and bias (deg/h). Spread a
// few ppm and a few mdeg/h about nominal; B04 and B11 out of the scale factor specification,
// B09 out of the bias one; B07 drifts +6 ppm a week.
struct Unit {
  double scale_factor_ppm;
  double bias_deg_h;
  double drift_ppm_per_test;
};

Unit unit_of(int i) {
  Unit u{2.0 * static_cast<double>((i * 7) % 11 - 5), 0.02 + 0.002 * static_cast<double>((i * 5) % 7 - 3), 0.0};
  if (i == 4) u.scale_factor_ppm = 80.0;
  if (i == 11) u.scale_factor_ppm = -90.0;
  if (i == 9) u.bias_deg_h = 0.09;
  if (i == 7) u.drift_ppm_per_test = 6.0;
  return u;
}

// A short campaign: the scale factor at three rates both ways and a 5-minute bias run.
std::string simulation_plan(const Unit& unit, int test) {
  const double ppm = unit.scale_factor_ppm + unit.drift_ppm_per_test * static_cast<double>(test);
  return fmt::format(
      "seed = 1\n[plan]\ntitle = \"Fleet demo: acceptance test of a production batch (simulated)\"\n"
      "[site]\nname = \"Harbin test hall 2 (virtual)\"\nlatitude_deg = 45.75\n"
      "[gyro]\noutput_unit = \"pulse/s\"\nsample_rate_hz = 100\nscale_factor = {}\nbias_deg_h = {}\n"
      "angle_random_walk_deg_rt_h = 0.0005\nbias_instability_deg_h = 0.003\n"
      "[rate_table]\nrate_error_ppm = 0.5\n"
      "[[test]]\nkind = \"scale_factor\"\nname = \"scale_factor\"\nrates_deg_s = [1, 10, 100]\n"
      "seconds_per_rate = 5\nstatic_seconds = 5\n"
      "[[test]]\nkind = \"bias\"\nname = \"bias\"\nseconds = 300\n",
      nominal_scale_factor * (1.0 + ppm * 1e-6), unit.bias_deg_h);
}

// The simulated processing plan with the specification limits added to its two procedures.
std::string with_limits(const std::string& plan) {
  const double lower = nominal_scale_factor * (1.0 - scale_factor_tolerance_ppm * 1e-6);
  const double upper = nominal_scale_factor * (1.0 + scale_factor_tolerance_ppm * 1e-6);
  std::string text;
  std::size_t start = 0;
  while (start < plan.size()) {
    std::size_t next = plan.find("\n[[procedure]]", start + 1);
    if (next == std::string::npos) next = plan.size();
    std::string block = plan.substr(start, next - start);
    if (block.find("kind = \"scale_factor\"") != std::string::npos) {
      block += fmt::format("\n[procedure.limits]\nscale_factor = {{ min = {}, max = {} }}\n", lower, upper);
    } else if (block.find("kind = \"bias\"") != std::string::npos) {
      block += fmt::format("\n[procedure.limits]\nbias = {{ max = {}, unit = \"deg/h\" }}\n", bias_limit_deg_h);
    }
    text += block;
    start = next;
  }
  return text;
}

}  // namespace

FleetDemoSummary run_fleet_demo(const std::string& out_dir, const FleetDemoOptions& options) {
  const std::filesystem::path out(out_dir);
  std::filesystem::create_directories(out);
  FleetDemoSummary summary;
  summary.archive_path = (out / "archive.sqlite").string();
  const auto store = archive::open_archive(summary.archive_path);
  const int tests = static_cast<int>(std::size(test_dates));
  for (int i = 0; i < instruments; ++i) {
    const std::string id = fmt::format("FOG-B{:02}", i + 1);
    for (int t = 0; t < tests; ++t) {
      if (options.progress) {
        options.progress("fleet " + id + " " + test_dates[t], static_cast<double>(i * tests + t) / (instruments * tests));
      }
      const std::filesystem::path dir = out / "campaigns" / id / test_dates[t];
      sim::SimulationOptions simulation;
      simulation.seed = 20260302u + 1000u * static_cast<unsigned>(i) + static_cast<unsigned>(t);
      simulation.instrument_id = id;
      simulation.date = test_dates[t];
      const sim::SimulationSummary lab =
          sim::simulate_text(simulation_plan(unit_of(i), t), "fleet demo plan", (dir / "lab").string(), simulation);
      std::ifstream plan_file(lab.plan_path, std::ios::binary);
      const std::string plan{std::istreambuf_iterator<char>(plan_file), {}};
      write_file_atomically(lab.plan_path, with_limits(plan));
      const CampaignSummary campaign = run_campaign(lab.plan_path, dir.string());
      if (store->add(campaign.results, campaign.written_files.front()).added) ++summary.campaigns_added;
    }
  }
  if (options.progress) options.progress("fleet pages", 1.0);
  const nlohmann::json data = archive::report_data(*store, store->figures(true));
  summary.fleet = data.at("fleet");
  summary.pages = report::write_archive_pages(data, out_dir, options.report);
  return summary;
}

std::string FleetDemoSummary::report() const {
  std::string text = fmt::format("inertest demo --fleet: {} campaigns added to {}\n", campaigns_added, archive_path);
  for (const auto& f : fleet) {
    text += fmt::format("\n{} ({}), {} instruments\n", f.at("figure").get<std::string>(), f.at("unit").get<std::string>(),
                        f.at("instruments").size());
    const auto& chart = f.at("control_chart");
    if (!chart.is_null()) {
      text += fmt::format("  center {:.8g}, UCL {:.8g}, LCL {:.8g}\n", chart.at("center").get<double>(),
                          chart.at("ucl").get<double>(), chart.at("lcl").get<double>());
      for (const auto& o : chart.at("out_of_control")) {
        text += fmt::format("  out of control: {} = {:.8g} ({})\n", o.at("instrument").get<std::string>(),
                            o.at("value").get<double>(), o.at("rule").get<std::string>());
      }
    }
    for (const char* index : {"cp", "cpk"}) {
      if (const auto& v = f.at("capability").at(index); !v.is_null()) text += fmt::format("  {} {:.4g}\n", index, v.get<double>());
    }
  }
  for (const auto& page : pages) text += "page: " + page + "\n";
  return text;
}

}  // namespace inertest
