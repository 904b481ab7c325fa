// Simulated multipoint tumble of an accelerometer on a dividing head (issue 18; plan kind
// "accelerometer_tumble", sim/dividing_head_tumble.h), at the site's gravity, with the dividing
// head's fixture error ([dividing_head] fixture_arcsec) as the mounting error. Keys: positions = 8,
// turns = 2, both_mountings = true, head_axis = "output" ("pendulous"), output_unit = "mA",
// noise = 2e-6 (output unit, each position's mean). Writes <name>/positions.csv. Truth: K0, K1, K2,
// K3, the misalignment, the cross-coupling and (both mountings) the mounting error, within 4 of
// the fit's reported sigma.
#include <fmt/format.h>

#include "inertest/sim/dividing_head_tumble.h"
#include "sim/generators.h"

namespace inertest::sim {

void generate_accelerometer_tumble(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  AccelerometerTumbleOptions options;
  options.positions = static_cast<std::size_t>(test.number_or("positions", 8.0));
  options.turns = static_cast<std::size_t>(test.number_or("turns", 2.0));
  options.both_mountings = test.boolean_or("both_mountings", true);
  const std::string head_axis = test.string_or("head_axis", "output");
  const std::string output_unit = test.string_or("output_unit", "mA");
  options.truth.noise = test.number_or("noise", options.truth.noise);
  options.truth.mounting_error_rad = lab.dividing_head_fixture_rad;
  options.head_along_output = head_axis == "output";
  options.gravity_m_s2 = lab.site.gravity_m_s2;
  if (options.positions != 8 && options.positions != 12 && options.positions != 16 && options.positions != 24) {
    test.fail_at("positions", "a tumble of 8, 12, 16 or 24 positions per turn identifies every term");
  }
  if (!(options.turns >= 1)) test.fail_at("turns", "at least one turn");
  if (head_axis != "output" && head_axis != "pendulous") test.fail_at("head_axis", "\"output\" or \"pendulous\"");
  if (!(options.truth.noise > 0.0)) test.fail_at("noise", "must be positive (the fit's uncertainty needs noise)");
  if (lab.dry_run) return;
  const std::string file = name + "/positions.csv";
  lab.write(file, simulate_accelerometer_tumble(options, lab.random(name + "/positions").seed()));
  lab.plan_steps += fmt::format(
      "[[procedure]]\nkind = \"accelerometer_tumble\"\nname = \"{}\"\nfile = \"{}\"\noutput_unit = \"{}\"\n"
      "head_axis = \"{}\"\n\n",
      name, file, output_unit, head_axis);
  const AccelerometerTumbleTruth& t = options.truth;
  const std::string basis = "4 sigma: the harmonic fit's covariance from its residuals (IEEE Std 1293-1998 8.3)";
  const auto add = [&](const char* quantity, const char* figure, double value, const std::string& unit) {
    lab.truth.push_back({name, quantity, figure, value, unit, 0.0, basis, 0.0, 4.0});
  };
  add("bias K0", "bias", t.bias_g, "g");
  add("scale factor K1", "scale_factor", t.scale_factor, output_unit + "/g");
  add("second-order coefficient K2", "second_order", t.second_order, "1/g");
  add("third-order coefficient K3", "third_order", t.third_order, "1/g^2");
  add("misalignment", options.head_along_output ? "misalignment_about_output_axis" : "misalignment_about_pendulous_axis",
      t.misalignment_rad, "rad");
  add("cross-coupling", options.head_along_output ? "cross_coupling_ip" : "cross_coupling_io", t.cross_coupling, "1/g");
  if (options.both_mountings) add("mounting error", "mounting_error", t.mounting_error_rad, "rad");
  lab.tests.push_back({{"name", name}, {"kind", "accelerometer_tumble"}, {"positions", options.positions},
                       {"turns", options.turns}, {"both_mountings", options.both_mountings}, {"head_axis", head_axis},
                       {"output_unit", output_unit}, {"noise", t.noise}});
}

}  // namespace inertest::sim
