// Accelerometer multipoint tumble test on a dividing head in the gravity field (IEEE Std 1293-1998:
// the model equation of 8.3, the multipoint tumble test of Part II and its analysis annex). Declared
// once (issue 22): the command `inertest accelerometer-tumble`, the plan kind
// "accelerometer_tumble", the JSON, the text, the report and the Python function come from this file.
//
// The model equation (IEEE Std 1293-1998 8.3, the terms a dividing head excites), accelerations in g:
//   E / K1 = K0 + a_i + K2 a_i^2 + K3 a_i^3 + delta_o a_p - delta_p a_o + K_ip a_i a_p + K_io a_i a_o.
// The head's axis is horizontal and lies along one of the accelerometer's other axes (`head_axis`):
// the output axis (OA), so that the input axis (IA) turns in the vertical IA-PA plane, or the
// pendulous axis (PA), so that it turns in the IA-OA plane; the remaining one is the cross axis.
// Convention (ours; the standard leaves the sense of the head to the test set-up): the head angle
// theta is the angle of the upward vertical from IA toward the cross axis, so that the specific
// force along IA is a_i = gamma cos(theta) and along the cross axis a_c = gamma sin(theta), where
// gamma = g_local / g_n (9.80665 m/s^2) is the site's gravity in g. A head turning the other way
// reads with angles negated.
//
// Expanding the model in harmonics of theta (cos^2 = (1 + cos 2t)/2, cos^3 = (3 cos t + cos 3t)/4,
// cos t sin t = sin 2t / 2), with c the misalignment (delta_o; -delta_p) and K_x the cross-coupling
// (K_ip; K_io) of the cross axis:
//   E = A0 + A1 cos t + B1 sin t + A2 cos 2t + B2 sin 2t + A3 cos 3t, where
//   A0 = K1 (K0 + K2 gamma^2 / 2)     A1 = K1 (gamma + 3 K3 gamma^3 / 4)   B1 = K1 c gamma
//   A2 = K1 K2 gamma^2 / 2            B2 = K1 K_x gamma^2 / 2              A3 = K1 K3 gamma^3 / 4
// The harmonics are fitted by linear least squares (their covariance from the residuals), and the
// coefficients follow by inverting these relations:
//   K1 = (A1 - 3 A3) / gamma, K0 = (A0 - A2) / K1, K2 = 2 A2 / (K1 gamma^2), K3 = 4 A3 / (K1 gamma^3),
//   c = B1 / (K1 gamma), K_x = 2 B2 / (K1 gamma^2),
// their uncertainties by first-order propagation of the harmonics' covariance. Equally spaced
// positions alias the harmonics above half their number: four positions identify A0, A1, B1 and
// A2 only (sin 2t vanishes and cos 3t equals cos t at 0, 90, 180 and 270 deg), so K3 and K_x are
// then not identified, taken as 0, and said so; eight positions or more identify all six.
//
// The mounting error. The fixture's reference for IA may itself lean by an angle e toward the
// head's cross direction (the direction of increasing theta); then a_i = gamma cos(theta - e), which
// adds K1 e gamma sin t to B1: one mounting measures c + e, not c. As the misalignment paper
// separates the instrument's misalignment from its fixture's (and GJB 2426A 5.15's four-position
// method, eq. 50 as corrected in the reference notes: delta = (delta_1 - delta_3) / 2), the tumble is
// repeated with the accelerometer turned 180 deg about its IA in the fixture (`mounting_deg` 180):
// the cross axis then points against the head's cross direction, so c and K_x change sign while e
// does not. With both mountings the fit takes B1 and B2 on s sin t and s sin 2t (s = +1 at 0 deg,
// -1 at 180 deg) and the mounting error E on sin t: c = B1 / (K1 gamma), e = E / (K1 gamma). (The
// error's second-order terms, K2 e and e^2, are left out.)
//
// The positions: a CSV with the header 'angle_deg,output', an optional 'run' column (repeated
// tumbles, fitted together) and an optional 'mounting_deg' column (0 or 180, above), one row per
// head position, the output being the mean of the accelerometer's output at that position in the
// instrument's output unit.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/figure.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/io/angle_column.h"
#include "inertest/io/text_table.h"
#include "inertest/core/units.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/numerics/statistics.h"
#include "inertest/procedures/instrument_sensor.h"

namespace inertest {
namespace {

struct AccelerometerTumbleOptions {
  std::string output_unit = "1";
  double gravity_m_s2 = constants::kStandardGravity;  // the site's gravity
  std::string head_axis = "output";                    // the accelerometer axis along the head's axis

  void validate() const {
    if (!(gravity_m_s2 > 9.7 && gravity_m_s2 < 9.9)) {
      throw ParameterError("gravity_m_s2", fmt::format("{} m/s^2 is not a gravity on the Earth's surface", gravity_m_s2));
    }
  }
};

struct TumblePosition {
  double angle_deg = 0.0;
  double output = 0.0;
  std::optional<double> run;
  bool turned = false;  // mounted turned 180 deg about IA (mounting_deg 180)
};

struct TumbleResidual {
  TumblePosition position;
  double model = 0.0;
};

struct AccelerometerTumbleResult {
  Figure bias;            // K0, g
  Figure scale_factor;    // K1, output unit / g
  Figure second_order;    // K2, g/g^2
  std::optional<Figure> third_order;  // K3, g/g^3; none with too few positions
  std::optional<Figure> misalignment_about_output_axis;     // delta_o, rad (head along OA)
  std::optional<Figure> misalignment_about_pendulous_axis;  // delta_p, rad (head along PA)
  std::optional<Figure> cross_coupling_ip;                  // K_ip, g/g^2 (head along OA)
  std::optional<Figure> cross_coupling_io;                  // K_io, g/g^2 (head along PA)
  std::optional<Figure> mounting_error;                     // e, rad (both mountings)
  Figure residual_rms;                                      // output unit
  std::size_t positions = 0;
  std::size_t degrees_of_freedom = 0;
  std::vector<TumbleResidual> residuals;
  std::string output_unit;
  std::vector<std::string> warnings;
};

std::vector<TumblePosition> read_tumble_positions(const std::string& path) {
  TextTableOptions options;
  options.header = TextTableOptions::Header::kPresent;
  const TextTable table = read_text_table(path, options);
  for (const char* name : {"angle_deg", "output"}) {
    if (!table.has_column(name)) {
      throw Error(SourceLocation{path, table.header_line, 1},
                  fmt::format("expected a header row naming the columns 'angle_deg' and 'output' (and optionally "
                              "'run'); '{}' is missing",
                              name));
    }
  }
  check_degrees_not_radians(table, "angle_deg");
  const auto& angles = table.column("angle_deg");
  const auto& outputs = table.column("output");
  const std::vector<double>* runs = table.has_column("run") ? &table.column("run") : nullptr;
  const std::vector<double>* mountings = table.has_column("mounting_deg") ? &table.column("mounting_deg") : nullptr;
  std::vector<TumblePosition> positions(table.rows());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    positions[i] = {angles[i], outputs[i], runs ? std::optional<double>((*runs)[i]) : std::nullopt};
    if (!mountings) continue;
    const double mounting = (*mountings)[i];
    if (mounting != 0.0 && mounting != 180.0) {
      const auto column = static_cast<std::size_t>(
          std::find(table.names.begin(), table.names.end(), "mounting_deg") - table.names.begin());
      throw Error(locate_cell(table, i, column),
                  fmt::format("mounting_deg is {}: 0 (as mounted) or 180 (turned about the input axis)", mounting));
    }
    positions[i].turned = mounting == 180.0;
  }
  return positions;
}

// The harmonics' columns, in the order of the header comment, then the mounting error's E; `fitted`
// says which are in the design.
constexpr std::size_t kHarmonics = 7;
enum Harmonic : std::size_t { kA0, kA1, kB1, kA2, kB2, kA3, kE };
constexpr std::array<const char*, kHarmonics> kHarmonicNames = {"A0",         "A1 (cos)",   "B1 (sin)",
                                                                 "A2 (cos 2)", "B2 (sin 2)", "A3 (cos 3)",
                                                                 "E (mounting, sin)"};

// The cosine and sine of an angle in degrees, reduced to [0, 360) and then to its quadrant first, so
// that a head angle read over several turns or written negative (450, -90) gives the same design as
// the angle within one turn, and multiples of 90 deg give exactly 0 and +-1. (sin(2 x 450 deg) in
// radians is 1.1e-16, not 0: four positions written 0..630 deg fitted K_ip from that rounding, 1.85e9
// +- 2.3e9 1/g, where 0..270 deg said it is not identified.)
double within_one_turn(double degrees) {
  double reduced = std::fmod(degrees, 360.0);  // exact
  if (reduced < 0.0) reduced += 360.0;
  return reduced >= 360.0 ? 0.0 : reduced;  // -1e-20 + 360 rounds to 360
}

std::array<double, 2> cos_sin_degrees(double degrees) {
  const double reduced = within_one_turn(degrees);
  const double quadrant = std::floor(reduced / 90.0);
  const double x = (reduced - 90.0 * quadrant) * constants::kDegree;  // in [0, pi / 2)
  const double c = std::cos(x), s = std::sin(x);
  switch (static_cast<int>(quadrant)) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
  }
}

// B1 and B2 follow the instrument's cross axis (s = -1 when turned), E the fixture's (header comment).
double harmonic_at(std::size_t h, const TumblePosition& position) {
  const double s = position.turned ? -1.0 : 1.0;
  const double angle = position.angle_deg;
  switch (h) {
    case kA0: return 1.0;
    case kA1: return cos_sin_degrees(angle)[0];
    case kB1: return s * cos_sin_degrees(angle)[1];
    case kA2: return cos_sin_degrees(2.0 * angle)[0];
    case kB2: return s * cos_sin_degrees(2.0 * angle)[1];
    case kA3: return cos_sin_degrees(3.0 * angle)[0];
    default: return cos_sin_degrees(angle)[1];
  }
}

struct HarmonicFit {
  std::array<double, kHarmonics> value{};
  std::array<std::array<double, kHarmonics>, kHarmonics> covariance{};
  std::array<bool, kHarmonics> fitted{};
  LeastSquaresResult fit;
};

HarmonicFit fit_harmonics(const std::vector<TumblePosition>& positions, std::array<bool, kHarmonics> fitted) {
  std::vector<std::size_t> columns;
  for (std::size_t h = 0; h < kHarmonics; ++h) {
    if (fitted[h]) columns.push_back(h);
  }
  Matrix design(positions.size(), columns.size());
  std::vector<double> outputs(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    for (std::size_t j = 0; j < columns.size(); ++j) design(i, j) = harmonic_at(columns[j], positions[i]);
    outputs[i] = positions[i].output;
  }
  LeastSquaresOptions options;
  options.require_full_rank = false;
  options.rank_tolerance = 1e-9;
  for (std::size_t h : columns) options.parameter_names.emplace_back(kHarmonicNames[h]);
  HarmonicFit result;
  result.fitted = fitted;
  result.fit = solve_least_squares(design, outputs, options);
  if (!result.fit.unidentifiable.empty()) return result;
  for (std::size_t j = 0; j < columns.size(); ++j) {
    result.value[columns[j]] = result.fit.parameters[j];
    for (std::size_t k = 0; k < columns.size(); ++k) {
      result.covariance[columns[j]][columns[k]] = result.fit.covariance(j, k);
    }
  }
  return result;
}

// The positions must spread over the whole turn (IEEE Std 1293-1998's multi-position tumble: equally
// spaced, 90 deg apart or closer): a largest gap between head angles (mod 360) over 120 deg is an
// Error naming it. Angles in radians (0 to 6.3 "deg") or a part of a turn (0 to 135 deg) gave a fit
// with figures a million times off and no word.
void require_whole_turn(const std::vector<TumblePosition>& positions, const std::string& path) {
  constexpr double kLargestGapDeg = 120.0;
  std::vector<double> angles;
  for (const TumblePosition& p : positions) angles.push_back(std::fmod(std::fmod(p.angle_deg, 360.0) + 360.0, 360.0));
  std::sort(angles.begin(), angles.end());
  if (angles.empty()) return;
  double gap = angles.front() + 360.0 - angles.back();  // across 0 deg
  double from = angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) {
    if (angles[i] - angles[i - 1] > gap) gap = angles[i] - angles[i - 1], from = angles[i - 1];
  }
  if (gap <= kLargestGapDeg) return;
  throw Error(SourceLocation{path, 0, 0},
              fmt::format("the head angles leave {:.4g} deg of the turn without a position (from {:.4g} deg on): a "
                          "tumble spreads its positions over the whole turn, {:g} deg apart at most (4, 8, 12, 16 or 24 "
                          "a turn); are the angles in radians? the column angle_deg is in degrees",
                          gap, from, kLargestGapDeg));
}

// The harmonics of the fullest model the positions identify: all six, else without A3 (K3), else
// without B2 (K_x) too; E besides when both mountings are there. Throws Error when even A0, A1, B1
// and A2 are not identified.
HarmonicFit identified_harmonics(const std::vector<TumblePosition>& positions, const std::string& path) {
  require_whole_turn(positions, path);
  const auto turned = [](const TumblePosition& p) { return p.turned; };
  const bool both_mountings = std::any_of(positions.begin(), positions.end(), turned) &&
                              !std::all_of(positions.begin(), positions.end(), turned);
  for (std::array<bool, kHarmonics> fitted : {std::array<bool, kHarmonics>{true, true, true, true, true, true},
                                              std::array<bool, kHarmonics>{true, true, true, true, true, false},
                                              std::array<bool, kHarmonics>{true, true, true, true, false, false}}) {
    fitted[kE] = both_mountings;
    if (positions.size() < static_cast<std::size_t>(std::count(fitted.begin(), fitted.end(), true))) continue;
    HarmonicFit fit = fit_harmonics(positions, fitted);
    if (fit.fit.unidentifiable.empty()) return fit;
  }
  throw Error(SourceLocation{path, 0, 0},
              fmt::format("the {} positions do not identify the bias, the scale factor, K2 and the misalignment: a "
                          "tumble needs at least 4 head angles spread over the circle (e.g. 0, 90, 180, 270 deg)",
                          positions.size()));
}

using Gradient = std::array<double, kHarmonics>;

Figure propagated(double value, const Gradient& gradient, const HarmonicFit& fit, const std::string& unit) {
  if (fit.fit.degrees_of_freedom == 0) return {value, unit, std::nullopt};
  double variance = 0.0;
  for (std::size_t j = 0; j < kHarmonics; ++j) {
    for (std::size_t k = 0; k < kHarmonics; ++k) variance += gradient[j] * fit.covariance[j][k] * gradient[k];
  }
  return {value, unit, std::sqrt(std::max(variance, 0.0))};
}

AccelerometerTumbleResult accelerometer_tumble(const std::vector<TumblePosition>& positions, const std::string& path,
                                               const AccelerometerTumbleOptions& options) {
  const HarmonicFit fit = identified_harmonics(positions, path);
  const auto& h = fit.value;
  const double gamma = options.gravity_m_s2 / constants::kStandardGravity;
  // K1 = (A1 - 3 A3) / gamma; every other coefficient is N / K1 with N linear in the harmonics, so
  // dK/dh = (dN/dh - K dK1/dh) / K1.
  const double k1 = (h[kA1] - 3.0 * h[kA3]) / gamma;
  if (!(std::abs(k1) > 0.0)) throw Error(SourceLocation{path, 0, 0}, "the output does not follow the input axis: K1 = 0");
  Gradient k1_gradient{};
  k1_gradient[kA1] = 1.0 / gamma;
  k1_gradient[kA3] = -3.0 / gamma;
  const auto ratio = [&](const Gradient& numerator, const std::string& unit) {
    double n = 0.0;
    for (std::size_t j = 0; j < kHarmonics; ++j) n += numerator[j] * h[j];
    const double value = n / k1;
    Gradient gradient{};
    for (std::size_t j = 0; j < kHarmonics; ++j) gradient[j] = (numerator[j] - value * k1_gradient[j]) / k1;
    return propagated(value, gradient, fit, unit);
  };
  const double gamma2 = gamma * gamma;
  AccelerometerTumbleResult result;
  result.output_unit = options.output_unit;
  result.scale_factor = propagated(k1, k1_gradient, fit, options.output_unit + "/g");
  result.bias = ratio({1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0}, "g");
  result.second_order = ratio({0.0, 0.0, 0.0, 2.0 / gamma2, 0.0, 0.0, 0.0}, "1/g");
  if (fit.fitted[kA3]) result.third_order = ratio({0.0, 0.0, 0.0, 0.0, 0.0, 4.0 / (gamma2 * gamma), 0.0}, "1/g^2");
  const bool head_along_output = options.head_axis == "output";
  // The model's cross-axis term is +delta_o a_p with the head along OA, -delta_p a_o along PA.
  const Figure misalignment = ratio({0.0, 0.0, (head_along_output ? 1.0 : -1.0) / gamma, 0.0, 0.0, 0.0, 0.0}, "rad");
  (head_along_output ? result.misalignment_about_output_axis : result.misalignment_about_pendulous_axis) = misalignment;
  if (fit.fitted[kB2]) {
    (head_along_output ? result.cross_coupling_ip : result.cross_coupling_io) =
        ratio({0.0, 0.0, 0.0, 0.0, 2.0 / gamma2, 0.0, 0.0}, "1/g");
  }
  if (fit.fitted[kE]) result.mounting_error = ratio({0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0 / gamma}, "rad");
  result.positions = positions.size();
  result.degrees_of_freedom = fit.fit.degrees_of_freedom;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    result.residuals.push_back({positions[i], positions[i].output - fit.fit.residuals[i]});
  }
  result.residual_rms = {fit.fit.residual_rms, options.output_unit, std::nullopt};
  if (!fit.fitted[kA3] || !fit.fitted[kB2]) {
    std::vector<double> angles;
    for (const TumblePosition& position : positions) angles.push_back(within_one_turn(position.angle_deg));
    std::sort(angles.begin(), angles.end());
    const auto distinct = static_cast<std::size_t>(std::unique(angles.begin(), angles.end()) - angles.begin());
    result.warnings.push_back(fmt::format(
        "{} positions{} do not identify {}: taken as 0 (equally spaced positions identify harmonics up to half their "
        "number; 8 positions or more identify every term)",
        positions.size(), distinct < positions.size() ? fmt::format(" at {} head angles", distinct) : "",
        !fit.fitted[kB2] ? (head_along_output ? "K3 and K_ip" : "K3 and K_io") : "K3"));
  }
  if (fit.fit.degrees_of_freedom == 0) {
    result.warnings.emplace_back(
        "as many positions as fitted terms: the fit is exact and gives no uncertainty (repeat the tumble, or add "
        "positions)");
  } else if (const std::optional<std::string> few =
                 few_degrees_of_freedom_warning("the fit", fit.fit.degrees_of_freedom, "tumbles")) {
    // 8 positions a turn leave 2: the 1-sigma held the truth in 53-58 % of trials, as Student's t says.
    result.warnings.push_back(*few + "; add positions or repeat the tumble");
  }
  return result;
}

nlohmann::json positions_json(const AccelerometerTumbleResult& result) {
  nlohmann::json rows = nlohmann::json::array();
  for (const TumbleResidual& r : result.residuals) {
    nlohmann::json row = {{"angle", Figure{r.position.angle_deg, "deg", std::nullopt}},
                          {"output", Figure{r.position.output, result.output_unit, std::nullopt}},
                          {"model", Figure{r.model, result.output_unit, std::nullopt}},
                          {"residual", Figure{r.position.output - r.model, result.output_unit, std::nullopt}}};
    if (r.position.run) row["run"] = *r.position.run;
    if (r.position.turned) row["mounting"] = Figure{180.0, "deg", std::nullopt};
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

ProcedureSpec accelerometer_tumble_spec();

ProcedureSpec accelerometer_tumble_spec() {
  using Options = AccelerometerTumbleOptions;
  using Result = AccelerometerTumbleResult;
  return ProcedureDefinition<Options, Result>(
             "accelerometer_tumble", "Accelerometer multipoint tumble", "IEEE Std 1293-1998 8.3",
             "the model equation's bias K0, scale factor K1, second- and third-order coefficients K2,\n"
             "K3, input-axis misalignment and cross-coupling, by least squares on the harmonics of the\n"
             "output over the dividing head's angle. POSITIONS is a CSV 'angle_deg,output[,run]\n"
             "[,mounting_deg]', one row per head position (4, 8, 12, 16 or 24 per turn); angle 0: input\n"
             "axis up, the angle turning the upward vertical from the input axis toward the cross axis.\n"
             "Tumbles at mounting_deg 0 and 180 (turned about the input axis in the fixture) separate the\n"
             "fixture's mounting error from the misalignment.")
      .chinese_title("加速度计多位置翻滚试验")
      .report_method(
          "The accelerometer is mounted on a dividing head whose axis is horizontal and along its output (or "
          "pendulous) axis, and its output is read at equally spaced head angles over a full turn. The output is "
          "fitted by least squares with the harmonics of the head angle that the model equation produces (cos θ, "
          "sin θ, cos 2θ, sin 2θ, cos 3θ), and the model's coefficients follow from the harmonics. When the tumble is "
          "repeated with the accelerometer turned 180° about its input axis in the fixture, the misalignment changes "
          "sign and the fixture's mounting error does not, which separates the two.",
          "将加速度计安装在水平轴分度头上，分度头轴沿输出轴（或摆轴），在一周内等间隔的分度头角位置读取输出。"
          "以模型方程产生的各次谐波（cos θ、sin θ、cos 2θ、sin 2θ、cos 3θ）对输出作最小二乘拟合，由谐波系数求得模型方程各系数。"
          "将加速度计在夹具中绕输入轴转180°重复翻滚时，失准角变号而夹具安装误差不变，由此将二者分离。")
      .example({"examples/accelerometer_tumble/positions.csv", "--output-unit", "mA", "--gravity", "9.7936"})
      .input(InputSpec("positions", "CSV of head angles and outputs").read_from_file("POSITIONS", "file"))
      .parameter(ParameterSpec("output_unit", "accelerometer output unit")
                     .instrument_gives("output_unit")
                     .instrument_gives_if(instrument_is_accelerometer),
                 &Options::output_unit)
      .parameter(ParameterSpec("gravity_m_s2", "local gravity")
                     .unit_is("m/s^2")
                     .command_line_name_is("gravity")
                     .site_gives("gravity_m_s2"),
                 &Options::gravity_m_s2)
      .parameter(ParameterSpec("head_axis", "accelerometer axis along the dividing head's axis").one_of(
                     {"output", "pendulous"}),
                 &Options::head_axis)
      .field({"bias", FieldRole::headline, "bias K0", "偏值 K0", "IEEE Std 1293-1998 8.3"}, &Result::bias)
      .field({"scale_factor", FieldRole::headline, "scale factor K1", "标度因数 K1", "IEEE Std 1293-1998 8.3"},
             &Result::scale_factor)
      .field({"second_order", FieldRole::headline, "second-order coefficient K2", "二阶非线性系数 K2",
              "IEEE Std 1293-1998 8.3"},
             &Result::second_order)
      .field({"third_order", FieldRole::headline, "third-order coefficient K3", "三阶非线性系数 K3",
              "IEEE Std 1293-1998 8.3"},
             &Result::third_order)
      .field({"misalignment_about_output_axis", FieldRole::headline, "misalignment about the output axis δo",
              "输入轴绕输出轴失准角 δo", "IEEE Std 1293-1998 8.3"},
             &Result::misalignment_about_output_axis)
      .field({"misalignment_about_pendulous_axis", FieldRole::headline, "misalignment about the pendulous axis δp",
              "输入轴绕摆轴失准角 δp", "IEEE Std 1293-1998 8.3"},
             &Result::misalignment_about_pendulous_axis)
      .field({"cross_coupling_ip", FieldRole::detail, "cross-coupling coefficient K_ip", "交叉耦合系数 K_ip",
              "IEEE Std 1293-1998 8.3"},
             &Result::cross_coupling_ip)
      .field({"cross_coupling_io", FieldRole::detail, "cross-coupling coefficient K_io", "交叉耦合系数 K_io",
              "IEEE Std 1293-1998 8.3"},
             &Result::cross_coupling_io)
      .field({"mounting_error", FieldRole::headline, "mounting error of the fixture (both mountings)",
              "安装误差（正反两种安装）", "IEEE Std 1293-1998 8.3; GJB 2426A-2004 5.15 eq. (50)"},
             &Result::mounting_error)
      .field({"residual_rms", FieldRole::detail, "rms residual of the fit", "拟合残差均方根", ""}, &Result::residual_rms)
      .field({"positions", FieldRole::detail, "positions", "位置数", ""}, &Result::positions)
      .field({"degrees_of_freedom", FieldRole::detail, "degrees of freedom", "自由度", ""}, &Result::degrees_of_freedom)
      .field_from({"residuals", FieldRole::curve, "residual at each head angle", "各分度头角位置的拟合残差", "",
                   {"angle", "residual"}},
                  positions_json)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &Result::warnings)
      .unit_of("bias", "g")
      .unit_of("scale_factor", "{output_unit}/g")
      .unit_of("second_order", "1/g")
      .unit_of("third_order", "1/g^2")
      .unit_of("misalignment_about_output_axis", "rad")
      .unit_of("misalignment_about_pendulous_axis", "rad")
      .unit_of("cross_coupling_ip", "1/g")
      .unit_of("cross_coupling_io", "1/g")
      .unit_of("mounting_error", "rad")
      .unit_of("residual_rms", "{output_unit}")
      .compute([](const ProcedureCall& call, const Options& options) {
        const std::string& path = call.files.at("positions");
        return accelerometer_tumble(read_tumble_positions(path), path, options);
      });
}

}  // namespace inertest
