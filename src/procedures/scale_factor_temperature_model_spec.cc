// Scale factor against temperature as a polynomial (issue 20), next to GJB 2426A-2004's one-number
// sensitivity Kt (5.8.5, eq. 13), from the same rate-table runs at several chamber temperatures:
// `inertest scale-factor-temperature-model RUNS`, the plan kind "scale_factor_temperature_model",
// its JSON, text, report and Python function come from this file.
//
// Each run's K_i is the scale factor of its test points (eqs. 1-6, with its standard error). The
// relative change y_i = (K_i/K_m − 1)·10^6 ppm against the room-temperature run K_m (5.8.5.3 a) is
// fitted by weighted least squares (weights 1/σ_i², σ_i = 10^6 σ(K_i)/K_m) as
//   y = c_0 + Σ_{j=1..n} k_Tj (T − T_m)^j,
// the temperature model of the scale factor in IEEE Std 952-1997's model equation (Annex B). The
// covariance is propagated from the K_i's uncertainties, Cov = G diag(σ²) Gᵀ with G the fit's linear
// map from observations to coefficients, so that it holds with as many runs as coefficients. When the
// points scatter about the polynomial more than their σ_i allow (χ²/ν > 1), the covariance is scaled
// by χ²/ν (the Birge ratio squared), with a warning when the excess is beyond chance; with ν = 0 it
// cannot be checked, and says so.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/io/procedure_inputs.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/procedures/scale_factor_temperature_sensitivity.h"

namespace inertest {
namespace {

struct ScaleFactorTemperatureModelOptions {
  ScaleFactorOptions scale_factor;
  std::optional<double> reference_temperature_degC;  // T_m; unset: the first run
  std::size_t order = 2;                             // n, the polynomial's order in T − T_m

  ScaleFactorTemperatureOptions sensitivity() const { return {scale_factor, reference_temperature_degC}; }
};

struct ScaleFactorTemperaturePoint {
  double temperature_degC = 0.0;
  Figure scale_factor;
  Figure relative_change;  // ppm
  double model_ppm = 0.0;
};

struct ScaleFactorTemperatureModelResult {
  nlohmann::json coefficients = nlohmann::json::object();  // figures by name: k_T0 (ppm), k_T, k_T2, ...
  Figure scale_factor_temperature_sensitivity;             // GJB's Kt, eq. (13)
  Figure reference_temperature;
  Figure reference_scale_factor;
  std::vector<ScaleFactorTemperaturePoint> points;
  std::vector<std::string> warnings;
};

ScaleFactorTemperatureModelResult fit_scale_factor_temperature(std::span<const TemperatureRun> runs,
                                                               const ScaleFactorTemperatureModelOptions& options) {
  const ScaleFactorTemperatureResult gjb = scale_factor_temperature_sensitivity(runs, options.sensitivity());
  ScaleFactorTemperatureModelResult result;
  result.scale_factor_temperature_sensitivity = gjb.scale_factor_temperature_sensitivity;
  result.reference_temperature = gjb.reference_temperature;
  result.reference_scale_factor = gjb.reference_scale_factor;
  result.warnings = gjb.warnings;
  const double km = gjb.reference_scale_factor.value;
  const double tm = gjb.reference_temperature.value;
  result.points.push_back({tm, gjb.reference_scale_factor, {}, 0.0});
  for (const auto& p : gjb.test_temperatures) result.points.push_back({p.temperature_degC, p.scale_factor, {}, 0.0});
  std::sort(result.points.begin(), result.points.end(),
            [](const auto& a, const auto& b) { return a.temperature_degC < b.temperature_degC; });
  const std::size_t m = result.points.size();
  const std::size_t n = options.order + 1;
  std::vector<double> y(m), sigma(m);
  Matrix design(m, n);
  for (std::size_t i = 0; i < m; ++i) {
    auto& p = result.points[i];
    y[i] = (p.scale_factor.value / km - 1.0) * 1e6;
    sigma[i] = p.scale_factor.uncertainty.value_or(0.0) / std::abs(km) * 1e6;  // u(Ki/Km), of either sign of K
    if (!(sigma[i] > 0.0)) throw Error(fmt::format("the scale factor at {} degC has no uncertainty", p.temperature_degC));
    p.relative_change = {y[i], "ppm", sigma[i]};
    for (std::size_t j = 0; j < n; ++j) design(i, j) = std::pow((p.temperature_degC - tm) / 10.0, static_cast<double>(j));
  }
  LeastSquaresOptions weighted;
  for (const double s : sigma) weighted.weights.push_back(1.0 / (s * s));
  const LeastSquaresResult fit = solve_least_squares(design, y, weighted);
  // G's column i: the coefficients fitted to the unit observation e_i.
  std::vector<double> variance(n, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    std::vector<double> unit(m, 0.0);
    unit[i] = 1.0;
    const LeastSquaresResult column = solve_least_squares(design, unit, weighted);
    for (std::size_t j = 0; j < n; ++j) variance[j] += column.parameters[j] * column.parameters[j] * sigma[i] * sigma[i];
  }
  // Lack of fit: χ² = Σ (r_i/σ_i)² on ν = m − n residual degrees of freedom. χ²/ν > 1
  // says the K_i scatter about the polynomial more than their uncertainties allow (an order too low, or
  // σ_i understated), and the covariance from the σ_i alone is too small: it is scaled by χ²/ν, the
  // square of the Birge ratio R_B = sqrt(χ²/ν) (R. T. Birge, Phys. Rev. 40 (1932) 207; Kacker, Datla &
  // Parr, Metrologia 39 (2002) 279), never scaled down.
  const std::size_t dof = m - n;
  double chi_square = 0.0;
  for (std::size_t i = 0; i < m; ++i) chi_square += (fit.residuals[i] / sigma[i]) * (fit.residuals[i] / sigma[i]);
  if (dof == 0) {
    result.warnings.push_back(fmt::format(
        "{} runs for a polynomial of order {}: the fit leaves no residual degree of freedom, so its uncertainties "
        "(from the runs' alone) cannot be checked against the points' scatter",
        m, options.order));
  } else if (chi_square / static_cast<double>(dof) > 1.0) {
    const double reduced = chi_square / static_cast<double>(dof);
    for (double& v : variance) v *= reduced;
    // Said when the scatter is beyond chance: χ²/ν more than 3 of its standard deviations sqrt(2/ν)
    // above 1, as the Allan fit judges its model (noise_terms.cc); a right model exceeds 1 half the time.
    if (reduced > 1.0 + 3.0 * std::sqrt(2.0 / static_cast<double>(dof))) {
      result.warnings.push_back(fmt::format(
        "the scale factors scatter about the polynomial of order {} more than their uncertainties allow: chi2/dof = "
        "{:.4g}/{} = {:.4g}; the coefficients' uncertainties are scaled by the Birge ratio sqrt(chi2/dof) = {:.4g} "
        "(a higher --order, or the runs' uncertainties understated?)",
        options.order, chi_square, dof, reduced, std::sqrt(reduced)));
    }
  }
  // The design is in (T − T_m)/10 for conditioning: k_Tj = β_j / 10^j.
  for (std::size_t j = 0; j < n; ++j) {
    const double scale = std::pow(10.0, static_cast<double>(j));
    const std::string name = j == 0 ? "k_T0" : j == 1 ? "k_T" : fmt::format("k_T{}", j);
    const std::string unit = j == 0 ? "ppm" : j == 1 ? "ppm/degC" : fmt::format("ppm/degC^{}", j);
    result.coefficients[name] = Figure{fit.parameters[j] / scale, unit, std::sqrt(variance[j]) / scale};
  }
  for (std::size_t i = 0; i < m; ++i) result.points[i].model_ppm = y[i] - fit.residuals[i];
  return result;
}

}  // namespace

ProcedureSpec scale_factor_temperature_model_spec() {
  using Options = ScaleFactorTemperatureModelOptions;
  using Result = ScaleFactorTemperatureModelResult;
  return ProcedureDefinition<Options, Result>(
             "scale_factor_temperature_model", "Scale factor temperature model",
             "IEEE Std 952-1997 Annex B; GJB 2426A-2004 5.8.5",
             "the relative change of K against the room-temperature run, (Ki/Km - 1) in ppm, fitted as a\n"
             "polynomial of --order in T - Tm by weighted least squares (weights from each K's standard\n"
             "error), next to GJB 2426A's one-number sensitivity Kt (eq. 13). RUNS is a CSV with the header\n"
             "'temperature_degC,file': one scale-factor test (rate,output) per temperature, as for\n"
             "scale-factor-temperature.")
      .chinese_title("标度因数温度模型")
      .report_method(
          "The scale factor of each rate-table run at a chamber temperature is computed as in 5.8.1; its relative "
          "change against the room-temperature run is fitted as a polynomial in temperature by weighted least "
          "squares, and shown next to the one-number sensitivity of eq. (13).",
          "按 5.8.1 计算各温度点的标度因数，相对室温标度因数的变化（ppm）用加权最小二乘拟合为温度多项式，并与式 (13) "
          "的标度因数温度灵敏度并列。")
      .example({"examples/scale_factor_temperature_model/runs.csv", "--output-unit", "pulse/s"})
      .input(InputSpec("runs", "one CSV of test points (rate,output) per temperature")
                 .numbered_runs("temperature_degC", "20:sf_20C.csv")
                 .listed_on_command_line("RUNS")
                 .at_least(2, "room temperature and a test temperature"))
      .parameter(ParameterSpec("order", "order of the polynomial in T - Tm"), &Options::order)
      .parameter(ParameterSpec("reference_temperature", "room temperature Tm (default: the first run)")
                     .unit_is("degC")
                     .plan_key_is("reference_temperature_degC"),
                 [](Options& options, const nlohmann::json& value) {
                   options.reference_temperature_degC = value.get<double>();
                 })
      .parameter(ParameterSpec("rate_unit", "unit of the rates"), &Options::scale_factor, &ScaleFactorOptions::rate_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &Options::scale_factor, &ScaleFactorOptions::output_unit)
      .field({"scale_factor_temperature_coefficients", FieldRole::detail, "model coefficients", "模型系数",
              "IEEE Std 952-1997 Annex B"},
             &Result::coefficients)
      .field({"scale_factor_temperature_sensitivity", FieldRole::headline, "GJB sensitivity Kt", "标度因数温度灵敏度",
              "GJB 2426A-2004 eq. (13)"},
             &Result::scale_factor_temperature_sensitivity)
      .field({"reference_scale_factor", FieldRole::detail, "reference Km", "室温标度因数", "5.8.5.3 a"},
             &Result::reference_scale_factor)
      .field({"reference_temperature", FieldRole::detail, "reference temperature Tm", "室温", "5.8.5.3 a"},
             &Result::reference_temperature)
      .field_from({"points", FieldRole::curve, "relative change of K against temperature", "标度因数相对变化-温度",
                   "IEEE Std 952-1997 Annex B", {"temperature", "relative_change", "model"}},
                  [](const Result& result) {
                    nlohmann::json points = nlohmann::json::array();
                    for (const auto& p : result.points) {
                      points.push_back({{"temperature", Figure{p.temperature_degC, "degC", std::nullopt}},
                                        {"scale_factor", p.scale_factor},
                                        {"relative_change", p.relative_change},
                                        {"model", Figure{p.model_ppm, "ppm", std::nullopt}}});
                    }
                    return points;
                  })
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .checked_by([](const ProcedureCall& call, const Options& options) {
        options.sensitivity().validate();
        if (options.order + 1 > call.runs.at("runs").size()) {
          throw ParameterError("order", fmt::format("order {} needs at least {} runs, got {}", options.order,
                                                    options.order + 1, call.runs.at("runs").size()));
        }
      })
      .unit_of("scale_factor_temperature_sensitivity", "ppm/degC")
      .unit_of("reference_scale_factor", "{output_unit}/({rate_unit})")
      .unit_of("reference_temperature", "degC")
      .compute([](const ProcedureCall& call, const Options& options) {
        std::vector<TemperatureRun> runs;
        for (const RunInput& run : call.runs.at("runs")) runs.push_back({run.number, read_scale_factor_points(run.file)});
        return fit_scale_factor_temperature(runs, options);
      });
}

}  // namespace inertest
