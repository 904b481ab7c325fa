// inertest archive repeatability ID --figure PROCEDURE/FIGURE [--db DB] [--json]
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "archive_command.h"
#include "inertest/core/units.h"
#include "inertest/procedures/bias_repeatability.h"
#include "inertest/procedures/scale_factor_repeatability.h"

namespace inertest::cli {
namespace {

struct Arguments {
  std::string instrument;
  std::string figure;
  std::string db;
  bool json = false;
};

// Writes a declared procedure's result (core/procedure_spec.h) into json["result"] and its text.
template <typename Result>
std::string write_result(const ProcedureSpec& spec, const Result& result, nlohmann::json& json) {
  const nlohmann::json fields = spec.fields_of(&result);
  json["result"] = procedure_json(spec, fields);
  return procedure_text(spec, fields);
}

// A scale factor is output per input (GJB 2426A 5.8.1, IEEE Std 1293 K1): named scale_factor (its
// output may be dimensionless: 1/(deg/s)), or of a unit that times an angular rate or an
// acceleration is an output's (pulse/s, V, mA, count), with no angle or length left (an IMU's
// count/(rad/s)). Eq. (12) is defined for it alone: not for the ppm of a repeatability or a
// sensitivity (scale_factor_temperature_sensitivity), nor for 1/g or deg/h/g coefficients.
bool is_scale_factor(const std::string& figure, const std::string& unit) {
  if (figure.substr(figure.rfind('/') + 1) == "scale_factor") return true;
  Dimension per_input;
  try {
    per_input = Unit::parse(unit).dimension();
  } catch (const Error&) {
    return false;
  }
  for (const char* input : {"rad/s", "m/s^2"}) {
    Dimension output = per_input;
    const Dimension input_dimension = Unit::parse(input).dimension();
    for (std::size_t base = 0; base < output.half_powers.size(); ++base) {
      output.half_powers[base] += input_dimension.half_powers[base];
    }
    if (output != Dimension{} && output.half_powers[Dimension::kAngle] == 0 &&
        output.half_powers[Dimension::kLength] == 0) {
      return true;
    }
  }
  return false;
}

CommandAction setup(CLI::App& archive) {
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = archive.add_subcommand(
      "repeatability",
      "Day-to-day repeatability of one instrument across its archived campaigns (one value per campaign):\n"
      "a scale factor by GJB 2426A-2004 5.8.4 eq. (12), Kr = (1/K̄)·[Σ(Ki − K̄)²/(Q − 1)]^½ in ppm; a bias\n"
      "(any figure in a rate unit) by 5.12.3 eq. (21), Br = [Σ(B0i − B̄0)²/(Q − 1)]^½ in deg/h. The standard\n"
      "asks for Q >= 6: fewer campaigns give a warning, fewer than 2 an error (no deviation from one).");
  command->add_option("ID", arguments->instrument, "instrument id")->required();
  command
      ->add_option("--figure", arguments->figure,
                   "PROCEDURE/FIGURE: a scale factor (e.g. scale_factor/scale_factor) or a bias "
                   "(e.g. bias/bias: the step's name, then the figure's key in results.json)")
      ->required();
  add_db_option(*command, arguments->db);
  command->add_flag("--json", arguments->json,
                    "print {\"instrument\", \"figure\", \"clause\", \"campaigns\", \"not_measured\" (the campaigns left "
                    "out), \"result\"}");
  return [arguments] {
    const auto store = open_archive_option(arguments->db);
    const archive::FigureHistory history = store->history(arguments->instrument, arguments->figure);
    // One value per campaign that measured the figure (in its unit); a campaign that did not is left
    // out, and said.
    std::vector<double> measured;
    std::vector<double> values;
    nlohmann::json campaigns = nlohmann::json::array();
    nlohmann::json not_measured = nlohmann::json::array();
    for (const auto& p : history.points) {
      (p.value ? campaigns : not_measured).push_back(p.campaign);
      if (p.value) measured.push_back(*p.value);
    }
    const std::size_t left_out = not_measured.size();
    if (measured.size() < 2 && left_out > 0) {
      throw Error(fmt::format("figure '{}' of '{}': {} of its {} campaigns did not measure it, which leaves {}: "
                              "repeatability needs at least 2",
                              history.figure, history.instrument, left_out, history.points.size(), measured.size()));
    }
    nlohmann::json json = {{"instrument", history.instrument}, {"figure", history.figure}, {"campaigns", campaigns},
                           {"not_measured", not_measured}};
    std::string report;
    if (converts(history.unit, "deg/h")) {
      for (const double v : measured) values.push_back(convert(v, history.unit, "deg/h"));
      json["clause"] = "GJB 2426A-2004 5.12.3, eq. (21)";
      report = write_result(*find_procedure_spec("bias_repeatability"), bias_repeatability(values), json);
    } else if (is_scale_factor(history.figure, history.unit)) {
      values = measured;
      ScaleFactorRepeatabilityOptions options;
      options.minimum_runs = 2;  // archived days, not a planned series: fewer than 6 is a warning
      json["clause"] = "GJB 2426A-2004 5.8.4, eq. (12)";
      report = write_result(*find_procedure_spec("scale_factor_repeatability"),
                            scale_factor_repeatability(values, history.unit, options), json);
    } else {
      throw Error("figure '" + history.figure + "' (" + history.unit +
                  "): repeatability is defined for a scale factor (GJB 2426A 5.8.4) or a bias in a rate unit (5.12.3)");
    }
    print_result(json, fmt::format("{} {} across {} campaigns{} ({}):\n{}", history.instrument, history.figure,
                                   values.size(),
                                   left_out == 0 ? std::string() : fmt::format(" ({} more did not measure it)", left_out),
                                   json["clause"].get<std::string>(), report),
                 arguments->json);
    return 0;
  };
}

const bool registered = register_archive_command("repeatability", setup);

}  // namespace
}  // namespace inertest::cli
