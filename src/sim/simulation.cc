#include "inertest/sim/simulation.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <toml++/toml.h>

#include "inertest/core/calendar_date.h"
#include "inertest/core/error.h"
#include "inertest/core/instrument_id.h"
#include "inertest/core/utf8.h"
#include "inertest/core/units.h"
#include "inertest/version.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

using campaign::PlanTable;

const std::map<std::string, TestGenerator, std::less<>>& generators() {
  static const std::map<std::string, TestGenerator, std::less<>> table = {
      {"scale_factor", generate_scale_factor},
      {"bias", generate_static},
      {"allan", generate_allan},
      {"centrifuge", generate_centrifuge},
      {"gyro_misalignment", generate_gyro_misalignment},
      {"input_axis_misalignment", generate_input_axis_misalignment},
      {"accelerometer_misalignment", generate_accelerometer_misalignment},
      {"bandwidth", generate_bandwidth},
      {"scale_factor_temperature", generate_scale_factor_temperature},
      {"scale_factor_repeatability", generate_scale_factor_repeatability},
      {"maximum_input_rate", generate_maximum_input_rate},
      {"bias_temperature", generate_bias_temperature},
      {"bias_repeatability", generate_bias_repeatability},
      {"turn_on_time", generate_turn_on_time},
      {"warm_up_time", generate_warm_up_time},
      {"polarity", generate_polarity},
      {"threshold", generate_threshold},
      {"resolution", generate_resolution},
      {"temperature_model", generate_temperature_model},
      {"imu_noise", generate_imu_noise},
      {"imu_tumble", generate_imu_tumble},
      {"accelerometer_tumble", generate_accelerometer_tumble},
  };
  return table;
}

std::array<double, 2> pair_or(PlanTable& table, std::string_view key, std::array<double, 2> fallback) {
  const auto values = table.optional_numbers(key);
  if (!values) return fallback;
  if (values->size() != 2) table.fail_at(key, "must hold two numbers");
  return {(*values)[0], (*values)[1]};
}

// A TOML basic string: the text in quotes, '"', '\\' and control characters escaped.
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (is_ascii_control(c)) {
      out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// The specification limits of a test (key `limits`, in the form of a processing plan's
// [procedure.limits]: figure = { min, max, unit }), checked here and written as the [procedure.limits]
// of the test's step, in the plan's order, so that `inertest run` gives a verdict per limit.
std::string limits_text(PlanTable& test) {
  auto table = test.optional_table("limits");
  if (!table) return "";
  std::vector<std::pair<std::string, toml::source_position>> entries;
  for (const auto& [key, node] : table->raw()) entries.emplace_back(std::string(key.str()), node.source().begin);
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return a.second.line != b.second.line ? a.second.line < b.second.line : a.second.column < b.second.column;
  });
  std::string text = "[procedure.limits]\n";
  for (const auto& [figure, position] : entries) {
    auto limit = table->optional_table(figure);
    const auto min = limit->optional_number("min");
    const auto max = limit->optional_number("max");
    const auto unit = limit->optional_string("unit");
    if (!min && !max) limit->fail("a limit needs 'min', 'max' or both");
    if (unit) {
      try {
        Unit::parse(*unit);
      } catch (const Error& e) {
        limit->fail_at("unit", e.message());
      }
    }
    limit->require_all_used();
    std::string fields;
    if (min) fields += "min = " + exact(*min);
    if (max) fields += (fields.empty() ? "" : ", ") + std::string("max = ") + exact(*max);
    if (unit) fields += ", unit = " + toml_string(*unit);
    text += fmt::format("{} = {{ {} }}\n", toml_string(figure), fields);
  }
  return text + "\n";
}

void read_gyro(PlanTable& table, GyroParameters& g) {
  g.id = table.string_or("id", g.id);
  g.output_unit = table.string_or("output_unit", g.output_unit);
  g.sample_rate_hz = table.number_or("sample_rate_hz", g.sample_rate_hz);
  g.scale_factor = table.number_or("scale_factor", g.scale_factor);
  g.maximum_rate_deg_s = table.number_or("maximum_rate_deg_s", g.maximum_rate_deg_s);
  g.nonlinearity_ppm = table.optional_numbers("nonlinearity_ppm").value_or(g.nonlinearity_ppm);
  g.asymmetry_ppm = table.number_or("asymmetry_ppm", g.asymmetry_ppm);
  g.scale_factor_temperature_ppm_per_c =
      table.number_or("scale_factor_temperature_ppm_per_c", g.scale_factor_temperature_ppm_per_c);
  g.bias_deg_h = table.number_or("bias_deg_h", g.bias_deg_h);
  g.scale_factor_repeatability_ppm = table.number_or("scale_factor_repeatability_ppm", g.scale_factor_repeatability_ppm);
  g.bias_repeatability_deg_h = table.number_or("bias_repeatability_deg_h", g.bias_repeatability_deg_h);
  g.bias_temperature_deg_h_per_c = table.number_or("bias_temperature_deg_h_per_c", g.bias_temperature_deg_h_per_c);
  g.reference_temperature_c = table.number_or("reference_temperature_c", g.reference_temperature_c);
  g.turn_on_bias_deg_h = table.number_or("turn_on_bias_deg_h", g.turn_on_bias_deg_h);
  g.turn_on_time_constant_s = table.number_or("turn_on_time_constant_s", g.turn_on_time_constant_s);
  g.quantization_arcsec = table.number_or("quantization_arcsec", g.quantization_arcsec);
  g.angle_random_walk_deg_rt_h = table.number_or("angle_random_walk_deg_rt_h", g.angle_random_walk_deg_rt_h);
  g.bias_instability_deg_h = table.number_or("bias_instability_deg_h", g.bias_instability_deg_h);
  g.rate_random_walk_deg_h_rt_h = table.number_or("rate_random_walk_deg_h_rt_h", g.rate_random_walk_deg_h_rt_h);
  g.rate_ramp_deg_h_h = table.number_or("rate_ramp_deg_h_h", g.rate_ramp_deg_h_h);
  g.flicker_correlation_s = pair_or(table, "flicker_correlation_s", g.flicker_correlation_s);
  g.bandwidth_hz = table.number_or("bandwidth_hz", g.bandwidth_hz);
  g.delay_ms = table.number_or("delay_ms", g.delay_ms);
  g.input_axis_misalignment_arcsec = pair_or(table, "input_axis_misalignment_arcsec", g.input_axis_misalignment_arcsec);
  if (auto drift = table.optional_table("drift")) {
    auto& d = g.drift;
    for (auto [key, field] : {std::pair{"DI", &d.DI}, {"DO", &d.DO}, {"DS", &d.DS}, {"DII", &d.DII}, {"DOO", &d.DOO},
                              {"DSS", &d.DSS}, {"DIO", &d.DIO}, {"DIS", &d.DIS}, {"DOS", &d.DOS}}) {
      *field = drift->number_or(key, *field);
    }
    if (drift->contains("DF")) drift->fail_at("DF", "is the gyro's bias_deg_h; set that instead");
    drift->require_all_used();
  }
  table.require_all_used();
  try {
    g.validate();
  } catch (const Error& e) {
    table.fail(e.message());
  }
}

SimulationSummary run(const toml::table& root, const std::string& source, const std::string& out_dir,
                      const SimulationOptions& options) {
  const std::string directory = std::filesystem::path(source).parent_path().string();
  PlanTable top(root, source, directory.empty() ? "." : directory, "simulation plan");
  Lab lab;
  lab.out_dir = out_dir;
  lab.plan_path = source;
  for (const char* written : {"plan.toml", "truth.json"}) lab.require_not_the_plan(written);
  lab.progress = options.progress;
  const double seed = top.number("seed");
  if (seed < 0 || seed != std::floor(seed) || seed > 9.007199254740992e15) top.fail_at("seed", "must be a whole number >= 0");
  lab.seed = options.seed.value_or(static_cast<std::uint64_t>(seed));
  std::string title = "simulated test campaign";
  std::string date = options.date;
  if (auto header = top.optional_table("plan")) {
    title = header->string_or("title", title);
    const std::string plan_date = header->string_or("date", "");
    if (date.empty()) date = plan_date;
    header->require_all_used();
  }
  // A day of the calendar, as the plan it writes must give (2024-02-30 was written, then refused by run).
  if (!date.empty() && !parse_calendar_date(date)) {
    throw Error(SourceLocation{source, 0, 0}, "test date '" + date + "': expected a day as YYYY-MM-DD");
  }
  if (auto site = top.optional_table("site")) {
    lab.site_name = site->string_or("name", "");
    lab.site.latitude_deg = site->number_or("latitude_deg", 0.0);
    if (lab.site.latitude_deg < -90 || lab.site.latitude_deg > 90) site->fail_at("latitude_deg", "must lie in [-90, 90]");
    lab.site.gravity_m_s2 = site->number_or("gravity_m_s2", normal_gravity(lab.site.latitude_deg));
    if (!(lab.site.gravity_m_s2 > 0)) site->fail_at("gravity_m_s2", "must be positive");
    site->require_all_used();
  } else {
    lab.site.gravity_m_s2 = normal_gravity(0.0);
  }
  auto gyro = top.optional_table("gyro");
  if (!gyro) top.fail("missing [gyro] table");
  read_gyro(*gyro, lab.gyro);
  // The id the written plan's [instrument] gives: held to the rules `inertest run` holds it to (it
  // took "LAB2/FOG-001", which run and the archive take, and wrote "..", which run refuses).
  if (const std::optional<std::string> problem = instrument_id_problem(lab.gyro.id)) gyro->fail_at("id", *problem);
  if (!options.instrument_id.empty()) {
    if (const std::optional<std::string> problem = instrument_id_problem(options.instrument_id)) {
      throw Error("--instrument: the instrument id " + *problem);
    }
    lab.gyro.id = options.instrument_id;
  }
  if (auto table = top.optional_table("rate_table")) {
    const auto tilt = pair_or(*table, "tilt_arcsec", {0, 0});
    const auto face = pair_or(*table, "face_arcsec", {0, 0});
    lab.rate_table.tilt_east_rad = tilt[0] * constants::kArcsecond;
    lab.rate_table.tilt_north_rad = tilt[1] * constants::kArcsecond;
    lab.rate_table.face_x_rad = face[0] * constants::kArcsecond;
    lab.rate_table.face_y_rad = face[1] * constants::kArcsecond;
    lab.rate_table.wobble_rad = table->number_or("wobble_arcsec", 0.0) * constants::kArcsecond;
    lab.rate_table.rate_error = table->number_or("rate_error_ppm", 0.0) * 1e-6;
    lab.fixture_tilt_rad = table->number_or("fixture_arcsec", 0.0) * constants::kArcsecond;
    table->require_all_used();
  }
  if (auto table = top.optional_table("dividing_head")) {
    lab.dividing_head_tilt_rad = table->number_or("tilt_arcsec", 0.0) * constants::kArcsecond;
    lab.dividing_head_fixture_rad = table->number_or("fixture_arcsec", 0.0) * constants::kArcsecond;
    table->require_all_used();
  }
  if (auto table = top.optional_table("accelerometer")) {
    auto& a = lab.accelerometer;
    a.id = table->string_or("id", a.id);
    a.output_unit = table->string_or("output_unit", a.output_unit);
    a.sample_rate_hz = table->number_or("sample_rate_hz", a.sample_rate_hz);
    a.scale_factor = table->number_or("scale_factor", a.scale_factor);
    a.bias_g = table->number_or("bias_mg", a.bias_g * 1e3) * 1e-3;
    a.misalignment_arcsec = pair_or(*table, "misalignment_arcsec", a.misalignment_arcsec);
    a.noise_ug_rt_hz = table->number_or("noise_ug_rt_hz", a.noise_ug_rt_hz);
    a.output_resolution = table->number_or("output_resolution", a.output_resolution);
    table->require_all_used();
    try {
      a.validate();
    } catch (const Error& e) {
      table->fail(e.message());
    }
  }
  if (auto table = top.optional_table("centrifuge")) {
    auto& c = lab.centrifuge;
    c.radius_m = table->number_or("radius_m", 1.0);
    if (!(c.radius_m > 0)) table->fail_at("radius_m", "must be positive");
    const auto sleeve = pair_or(*table, "sleeve_arcsec", {0, 0});
    const auto perpendicularity = pair_or(*table, "perpendicularity_arcsec", {0, 0});
    c.errors.x1t = sleeve[0] * constants::kArcsecond;
    c.errors.y1t = sleeve[1] * constants::kArcsecond;
    c.errors.x2t = perpendicularity[0] * constants::kArcsecond;
    c.errors.y2t = perpendicularity[1] * constants::kArcsecond;
    c.errors.wobble2 = table->number_or("wobble_arcsec", 0.0) * constants::kArcsecond;
    c.errors.platform_rate_error = table->number_or("platform_rate_error_rad_s", 0.0);
    table->require_all_used();
  }
  auto tests = top.tables("test");
  if (tests.empty()) top.fail("no [[test]] tables: nothing to simulate");
  std::vector<std::pair<TestGenerator, std::string>> prepared;
  std::vector<std::string> limits;
  std::map<std::string, int> names;
  for (auto& test : tests) {
    const std::string kind = test.string("kind");
    const auto found = generators().find(kind);
    if (found == generators().end()) {
      std::string known;
      for (const auto& [k, g] : generators()) known += (known.empty() ? "" : ", ") + k;
      test.fail_at("kind", "'" + kind + "' cannot be simulated (known: " + known + ")");
    }
    const std::string name = test.string_or("name", kind);
    if (name.empty() || name.find_first_of("/\\\"") != std::string::npos || name.front() == '.' ||
        std::any_of(name.begin(), name.end(), is_ascii_control)) {
      test.fail_at("name", "must be a plain file name");
    }
    if (names[name]++ > 0) test.fail_at("name", "'" + name + "' names two tests");
    limits.push_back(limits_text(test));
    lab.dry_run = true;
    found->second(test, name, lab);
    test.require_all_used();
    prepared.emplace_back(found->second, name);
  }
  top.require_all_used();

  lab.dry_run = false;
  for (std::size_t i = 0; i < prepared.size(); ++i) {
    if (options.progress) options.progress("simulate " + prepared[i].second, static_cast<double>(i) / prepared.size());
    prepared[i].first(tests[i], prepared[i].second, lab);
    lab.plan_steps += limits[i];
  }
  if (options.progress) options.progress("simulated", 1.0);

  const GyroParameters& g = lab.gyro;
  std::string plan = fmt::format(
      "# Processing plan written by inertest simulate (seed {}): run it with\n"
      "#   inertest run plan.toml --out results\n"
      "[plan]\ntitle = {}\n{}\n[instrument]\nid = {}\ntype = \"gyro\"\noutput_unit = {}\n"
      "nominal_scale_factor = {}\nsample_rate_hz = {}\n\n[site]\nname = {}\nlatitude_deg = {}\n"
      "gravity_m_s2 = {}\n\n",
      lab.seed, toml_string(title), date.empty() ? std::string() : "date = \"" + date + "\"\n", toml_string(g.id),
      toml_string(g.output_unit), exact(g.scale_factor), exact(g.sample_rate_hz), toml_string(lab.site_name),
      exact(lab.site.latitude_deg), exact(lab.site.gravity_m_s2));
  plan += lab.plan_steps;
  SimulationSummary summary;
  summary.plan_path = (std::filesystem::path(out_dir) / "plan.toml").string();
  lab.write("plan.toml", plan);

  nlohmann::json truth = nlohmann::json::array();
  for (const auto& t : lab.truth) {
    nlohmann::json entry = {{"procedure", t.procedure}, {"quantity", t.quantity}, {"true", t.value},
                            {"systematic", t.systematic}, {"expected", t.value + t.systematic},
                            {"unit", t.unit},           {"tolerance", t.tolerance}, {"basis", t.basis}};
    if (t.tolerance_sigmas > 0.0) entry["tolerance_sigmas"] = t.tolerance_sigmas;
    entry["figure"] = t.figure.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.figure);
    truth.push_back(entry);
  }
  summary.truth = {
      {"inertest_version", version()},
      {"seed", lab.seed},
      {"site", {{"name", lab.site_name}, {"latitude_deg", lab.site.latitude_deg}, {"gravity_m_s2", lab.site.gravity_m_s2}}},
      {"gyro", g.to_json()},
      {"accelerometer", lab.accelerometer.to_json()},
      {"tests", lab.tests},
      {"truth", truth},
  };
  lab.write("truth.json", summary.truth.dump(2) + "\n");
  summary.written_files = lab.written_files;
  return summary;
}

toml::table parse(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw Error(SourceLocation{source, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)},
                std::string(e.description()));
  }
}

}  // namespace

SimulationSummary simulate(const std::string& plan_path, const std::string& out_dir, const SimulationOptions& options) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(plan_path, error)) throw Error(SourceLocation{plan_path, 0, 0}, "simulation plan not found");
  try {
    const toml::table root = toml::parse_file(plan_path);
    return run(root, plan_path, out_dir, options);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw Error(SourceLocation{plan_path, static_cast<std::size_t>(begin.line), static_cast<std::size_t>(begin.column)},
                std::string(e.description()));
  }
}

SimulationSummary simulate_text(std::string_view plan_text, const std::string& source, const std::string& out_dir,
                                const SimulationOptions& options) {
  const toml::table root = parse(plan_text, source);
  return run(root, source, out_dir, options);
}

}  // namespace inertest::sim
