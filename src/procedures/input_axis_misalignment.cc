#include "inertest/procedures/input_axis_misalignment.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "inertest/io/text_table.h"
#include "inertest/numerics/statistics.h"

namespace inertest {
namespace {

using constants::kArcsecond;
using constants::kDegree;

Figure arcsec(double angle_rad) { return {angle_rad / kArcsecond, "arcsec", std::nullopt}; }

double angle_from_components(double sum_of_squares) {
  const double sine = std::sqrt(sum_of_squares);
  if (sine > 1.0) {
    throw Error(fmt::format("input-axis misalignment: sqrt(sum of delta^2) = {:.6g} > 1; check the scale factor, the "
                            "rate and the outputs (K must be output per deg/s)",
                            sine));
  }
  return std::asin(sine);  // eqs. (49)-(50)
}

}  // namespace

void InputAxisMisalignmentOptions::validate() const {
  if (!std::isfinite(scale_factor) || scale_factor == 0.0) {
    throw Error("input-axis misalignment: the scale factor K must be nonzero (output unit per deg/s)");
  }
  if (!std::isfinite(rate) || rate <= 0.0) throw Error("input-axis misalignment: the table rate must be positive");
  if (Unit::parse(rate_unit).dimension() != Unit::parse("rad/s").dimension()) {
    throw Error("input-axis misalignment: rate unit '" + rate_unit + "' is not an angular rate");
  }
  Unit::parse(output_unit);
}

InputAxisMisalignmentResult input_axis_misalignment(std::span<const MisalignmentPosition> positions,
                                                    const InputAxisMisalignmentOptions& options) {
  options.validate();
  if (positions.size() != 2 && positions.size() != 4) {
    throw Error(fmt::format("input-axis misalignment: {} position(s); GJB 2426A 5.15.3 uses 2 positions, or 4 to "
                            "remove the mounting error",
                            positions.size()));
  }
  const double rate_deg_s = convert(options.rate, options.rate_unit, "deg/s");
  std::vector<double> delta;
  for (std::size_t j = 0; j < positions.size(); ++j) {
    const auto& p = positions[j];
    if (!std::isfinite(p.output_positive) || !std::isfinite(p.output_negative)) {
      throw Error(fmt::format("input-axis misalignment: position {}: output is not finite", j + 1));
    }
    // Eqs. (47)-(48) with K in output per input: δ = (F+ − F−)/(2·K·Ω), dimensionless (rad), K per
    // deg/s as threshold and resolution take it, Ω in deg/s whatever unit it is given in.
    delta.push_back((p.output_positive - p.output_negative) / (2.0 * options.scale_factor * rate_deg_s));
  }

  InputAxisMisalignmentResult result;
  for (double d : delta) result.deltas.push_back(arcsec(d));
  double alpha = 0.0;
  if (delta.size() == 2) {
    alpha = angle_from_components(delta[0] * delta[0] + delta[1] * delta[1]);  // eq. (49)
  } else {
    const double toward_ox = 0.5 * (delta[0] - delta[2]);
    const double toward_oy = 0.5 * (delta[1] - delta[3]);
    alpha = angle_from_components(toward_ox * toward_ox + toward_oy * toward_oy);
    result.misalignment_toward_ox = arcsec(toward_ox);
    result.misalignment_toward_oy = arcsec(toward_oy);
    result.mounting_error = arcsec(0.25 * (delta[0] + delta[1] + delta[2] + delta[3]));
    double printed = 0.0;
    for (double d : delta) printed += d * d;
    result.misalignment_eq50_as_printed = arcsec(angle_from_components(printed));  // eq. (50) verbatim
  }
  result.misalignment = arcsec(alpha);
  result.misalignment_deg = {alpha / kDegree, "deg", std::nullopt};
  // A stuck channel gives F+ = F- at every position, which reads as a perfectly aligned input axis.
  std::vector<double> outputs;
  for (const auto& p : positions) outputs.insert(outputs.end(), {p.output_positive, p.output_negative});
  if (is_constant(outputs)) {
    result.warnings.push_back(fmt::format("every output equals {:.10g} {} (a stuck channel?); angles of 0 arcsec from "
                                          "it are not a measurement",
                                          outputs.front(), options.output_unit));
  }
  return result;
}

std::vector<MisalignmentPosition> read_misalignment_positions(const std::string& path) {
  TextTableOptions read;
  read.columns = {ColumnSelector{"position"}, ColumnSelector{"output_positive"}, ColumnSelector{"output_negative"}};
  read.header = TextTableOptions::Header::kPresent;
  const TextTable table = read_text_table(path, read);
  std::vector<MisalignmentPosition> positions;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    if (table.columns[0][i] != static_cast<double>(i + 1)) {
      throw Error(SourceLocation{path, table.row_lines.empty() ? 0 : table.row_lines[i], 0},
                  fmt::format("expected position {} (positions 1, 2[, 3, 4] in order), found {}", i + 1,
                              table.columns[0][i]));
    }
    positions.push_back({table.columns[1][i], table.columns[2][i]});
  }
  return positions;
}

}  // namespace inertest
