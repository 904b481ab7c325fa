#include "inertest/procedures/temperature_model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/json_text.h"
#include "inertest/core/test_temperature.h"
#include "inertest/core/units.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/output_record.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/numerics/statistics.h"
#include "io/text_rows.h"
#include "procedures/temperature_model_internal.h"

namespace inertest {
namespace {

constexpr double kSecondsPerHour = 3600.0;
constexpr double kSecondsPerMinute = 60.0;
constexpr std::size_t kHighestOrder = 6;  // of the polynomial in ΔT (maximum_order)

std::string power_name(std::size_t k) { return k == 1 ? "D_T" : fmt::format("D_T{}", k); }
std::string power_unit(std::size_t k) { return k == 1 ? "deg/h/degC" : fmt::format("deg/h/degC^{}", k); }

// The terms of the model equation (procedures/temperature_model.h) a coefficient multiplies.
enum class ThermalTerm { power, rate, temperature_rate, hysteresis };

struct TermOfCoefficient {
  ThermalTerm term = ThermalTerm::power;
  std::size_t power = 0;  // of ΔT, for ThermalTerm::power
};

// The term of a coefficient by its name: D_0, D_T, D_T2 ... D_T6, D_dT, D_TdT, D_H; none for another.
// Read, not formatted: thermal_bias_deg_h asks at every interval.
std::optional<TermOfCoefficient> term_of(const std::string& name) {
  if (name == "D_0") return TermOfCoefficient{ThermalTerm::power, 0};
  if (name == "D_T") return TermOfCoefficient{ThermalTerm::power, 1};
  if (name == "D_dT") return TermOfCoefficient{ThermalTerm::rate, 0};
  if (name == "D_TdT") return TermOfCoefficient{ThermalTerm::temperature_rate, 0};
  if (name == "D_H") return TermOfCoefficient{ThermalTerm::hysteresis, 0};
  if (name.size() == 4 && name.starts_with("D_T") && name[3] >= '2' &&
      static_cast<std::size_t>(name[3] - '0') <= kHighestOrder) {
    return TermOfCoefficient{ThermalTerm::power, static_cast<std::size_t>(name[3] - '0')};
  }
  return std::nullopt;
}

// The unit the model takes the coefficient of a term in.
std::string unit_of(const TermOfCoefficient& term) {
  switch (term.term) {
    case ThermalTerm::power: return term.power == 0 ? "deg/h" : power_unit(term.power);
    case ThermalTerm::rate: return "deg/h/(degC/min)";
    case ThermalTerm::temperature_rate: return "deg/h/degC/(degC/min)";
    case ThermalTerm::hysteresis: return "deg/h";
  }
  return "deg/h";
}

// A coefficient of an exported file (named `what` in messages: its key or row, at `where`, its unit at
// `unit_where`), its value and uncertainty converted from the unit it gives to the unit the model takes.
ThermalCoefficient checked_coefficient(const std::string& name, const Figure& given, const SourceLocation& where,
                                       const SourceLocation& unit_where, const std::string& what) {
  const std::optional<TermOfCoefficient> term = term_of(name);
  if (!term) {
    throw Error(where, fmt::format("{}: unknown coefficient '{}' (the model's are D_0, D_T, D_T2 ... D_T{}, D_dT, "
                                   "D_TdT and D_H)",
                                   what, name, kHighestOrder));
  }
  const std::string unit = unit_of(*term);
  if (given.unit.empty()) {
    throw Error(unit_where, fmt::format("{}: no unit (the model takes {} in {})", what, name, unit));
  }
  try {
    const Unit from = Unit::parse(given.unit);
    const Unit to = Unit::parse(unit);
    std::optional<double> uncertainty;
    if (given.uncertainty) uncertainty = convert(*given.uncertainty, from, to);
    return {name, {convert(given.value, from, to), unit, uncertainty}};
  } catch (const Error& e) {
    throw Error(unit_where, fmt::format("{}: the unit '{}' of {} is not one of {}: {}", what, given.unit, name,
                                        unit, e.message()));
  }
}

// Every term a model of its coefficients needs is there: D_0; D_T ... D_Tn without a gap, n the
// model's order (`order` when the file states it, else the highest power given); D_dT with D_TdT.
void check_complete_model(std::span<const ThermalCoefficient> coefficients, std::optional<std::size_t> order,
                          const SourceLocation& where) {
  std::vector<bool> powers(kHighestOrder + 1, false);
  bool rate = false, temperature_rate = false;
  std::size_t highest = 0;
  for (const ThermalCoefficient& c : coefficients) {
    const TermOfCoefficient term = *term_of(c.name);
    if (term.term == ThermalTerm::power) {
      powers[term.power] = true;
      highest = std::max(highest, term.power);
    }
    rate = rate || term.term == ThermalTerm::rate;
    temperature_rate = temperature_rate || term.term == ThermalTerm::temperature_rate;
  }
  if (order && highest > *order) {
    throw Error(where, fmt::format("coefficients: {} is beyond the model's order {}", power_name(highest), *order));
  }
  const std::size_t n = order.value_or(highest);
  for (std::size_t k = 0; k <= n; ++k) {
    if (powers[k]) continue;
    throw Error(where, fmt::format("coefficients: {} is missing (a model of order {} has D_0{})",
                                   k == 0 ? "D_0" : power_name(k), n,
                                   n == 0 ? "" : n == 1 ? " and D_T" : fmt::format(", D_T ... {}", power_name(n))));
  }
  if (rate != temperature_rate) {
    throw Error(where, fmt::format("coefficients: {} is missing (the rate terms D_dT and D_TdT come together)",
                                   rate ? "D_TdT" : "D_dT"));
  }
}

// The columns of the design in the scaled variables u = (T − T_c)/s, v = Ṫ/r: u^0..u^n, then v and
// u·v with the rate terms, then h with both legs present.
struct Design {
  std::size_t order = 0;
  bool rate_terms = true;
  bool hysteresis = true;
  double centre = 0.0;  // T_c
  double half_range = 1.0;  // s
  double rate_scale = 1.0;  // r, degC/min

  std::size_t columns() const { return order + 1 + (rate_terms ? 2 : 0) + (hysteresis ? 1 : 0); }

  void row(const thermal::Interval& interval, double temperature, std::span<double> out) const {
    const double u = (temperature - centre) / half_range;
    double power = 1.0;
    for (std::size_t k = 0; k <= order; ++k, power *= u) out[k] = power;
    std::size_t c = order + 1;
    if (rate_terms) {
      const double v = interval.rate_degC_per_min / rate_scale;
      out[c++] = v;
      out[c++] = u * v;
    }
    if (hysteresis) out[c] = 0.5 * interval.leg;
  }

  Matrix matrix(std::span<const thermal::Interval> intervals, std::size_t sensor) const {
    Matrix a(intervals.size(), columns());
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      row(intervals[i], intervals[i].temperature_degC[sensor], std::span<double>(&a(i, 0), a.cols));
    }
    return a;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> names{"D_0"};
    for (std::size_t k = 1; k <= order; ++k) names.push_back(power_name(k));
    if (rate_terms) names.insert(names.end(), {"D_dT", "D_TdT"});
    if (hysteresis) names.push_back("D_H");
    return names;
  }

  std::vector<std::string> units() const {
    std::vector<std::string> units{"deg/h"};
    for (std::size_t k = 1; k <= order; ++k) units.push_back(power_unit(k));
    if (rate_terms) units.insert(units.end(), {"deg/h/(degC/min)", "deg/h/degC/(degC/min)"});
    if (hysteresis) units.push_back("deg/h");
    return units;
  }

  // M with θ = M β: the physical coefficients about T_ref (ΔT = T − T_ref = x) from the scaled ones.
  // u^j = ((x + d)/s)^j = Σ_k C(j, k) d^(j−k) x^k / s^j with d = T_ref − T_c; v = Ṫ/r;
  // u·v = x·Ṫ/(s r) + d·Ṫ/(s r).
  Matrix physical_map(double reference) const {
    const std::size_t n = columns();
    Matrix m(n, n);
    const double d = reference - centre;
    for (std::size_t j = 0; j <= order; ++j) {
      double binomial = 1.0;
      for (std::size_t k = 0; k <= j; ++k) {
        m(k, j) = binomial * std::pow(d, static_cast<double>(j - k)) / std::pow(half_range, static_cast<double>(j));
        binomial = binomial * static_cast<double>(j - k) / static_cast<double>(k + 1);
      }
    }
    std::size_t c = order + 1;
    if (rate_terms) {
      m(c, c) = 1.0 / rate_scale;
      m(c, c + 1) = d / (half_range * rate_scale);
      m(c + 1, c + 1) = 1.0 / (half_range * rate_scale);
      c += 2;
    }
    if (hysteresis) m(c, c) = 1.0;
    return m;
  }
};

std::vector<double> biases(std::span<const thermal::Interval> intervals) {
  std::vector<double> b;
  for (const auto& interval : intervals) b.push_back(interval.bias_deg_h);
  return b;
}

std::vector<double> predict(const Matrix& a, const std::vector<double>& beta) {
  std::vector<double> y(a.rows, 0.0);
  for (std::size_t i = 0; i < a.rows; ++i) {
    for (std::size_t c = 0; c < a.cols; ++c) y[i] += a(i, c) * beta[c];
  }
  return y;
}

// Step 4: k-fold cross-validation on contiguous blocks; the mean square of the held-out errors and
// its standard error across folds.
OrderScore cross_validate(const Design& design, std::span<const thermal::Interval> intervals, std::size_t sensor,
                          std::size_t folds) {
  const Matrix a = design.matrix(intervals, sensor);
  const std::vector<double> y = biases(intervals);
  const std::size_t n = intervals.size();
  std::vector<double> fold_mean_squares;
  double total = 0.0;
  LeastSquaresOptions loose;
  loose.require_full_rank = false;
  for (std::size_t f = 0; f < folds; ++f) {
    const std::size_t begin = f * n / folds;
    const std::size_t end = (f + 1) * n / folds;
    Matrix train(n - (end - begin), a.cols);
    std::vector<double> train_y;
    for (std::size_t i = 0, r = 0; i < n; ++i) {
      if (i >= begin && i < end) continue;
      std::copy_n(a.data.begin() + static_cast<std::ptrdiff_t>(i * a.cols), a.cols, &train(r++, 0));
      train_y.push_back(y[i]);
    }
    const LeastSquaresResult fit = solve_least_squares(train, train_y, loose);
    double sum = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      double predicted = 0.0;
      for (std::size_t c = 0; c < a.cols; ++c) predicted += a(i, c) * fit.parameters[c];
      sum += (y[i] - predicted) * (y[i] - predicted);
    }
    total += sum;
    fold_mean_squares.push_back(sum / static_cast<double>(end - begin));
  }
  return {design.order, std::sqrt(total / static_cast<double>(n)),
          sample_standard_deviation(fold_mean_squares) / std::sqrt(static_cast<double>(folds))};
}

struct SensorModel {
  Design design;
  LeastSquaresResult fit;
  std::vector<OrderScore> scores;
};

SensorModel fit_sensor(std::span<const thermal::Interval> intervals, std::size_t sensor, bool hysteresis,
                       const TemperatureModelOptions& options) {
  Design design;
  design.rate_terms = options.rate_terms;
  design.hysteresis = hysteresis;
  double low = std::numeric_limits<double>::infinity(), high = -low, rate = 0.0;
  for (const auto& interval : intervals) {
    low = std::min(low, interval.temperature_degC[sensor]);
    high = std::max(high, interval.temperature_degC[sensor]);
    rate = std::max(rate, std::abs(interval.rate_degC_per_min));
  }
  design.centre = 0.5 * (low + high);
  design.half_range = high > low ? 0.5 * (high - low) : 1.0;
  design.rate_scale = rate > 0.0 ? rate : 1.0;
  SensorModel model;
  for (std::size_t order = 0; order <= options.maximum_order; ++order) {
    design.order = order;
    model.scores.push_back(cross_validate(design, intervals, sensor, options.folds));
  }
  // The one-standard-error rule on the mean squares.
  const auto best = std::min_element(model.scores.begin(), model.scores.end(),
                                     [](const OrderScore& a, const OrderScore& b) { return a.cv_rms_deg_h < b.cv_rms_deg_h; });
  const double bound = best->cv_rms_deg_h * best->cv_rms_deg_h + best->cv_standard_error;
  design.order = std::find_if(model.scores.begin(), model.scores.end(), [&](const OrderScore& s) {
                   return s.cv_rms_deg_h * s.cv_rms_deg_h <= bound;
                 })->order;
  LeastSquaresOptions strict;
  strict.parameter_names = design.names();
  strict.serially_correlated = true;  // a gyro's drift carries over from one interval to the next
  model.fit = solve_least_squares(design.matrix(intervals, sensor), biases(intervals), strict);
  model.design = design;
  return model;
}

// GJB 2426A-2004 eq. (20): the sample standard deviation of the window means (m intervals each), with
// its 1-sigma s/sqrt(2(n − 1)) for n windows.
Figure window_stability(std::span<const double> values, std::size_t m) {
  const std::vector<double> means = window_means(values, m);
  if (means.size() < 2) throw Error("the record holds fewer than two bias stability windows");
  const double s = sample_standard_deviation(means);
  return {s, "deg/h", s / std::sqrt(2.0 * static_cast<double>(means.size() - 1))};
}

std::size_t window_intervals(double window_s, double interval_s) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(window_s / interval_s)));
}

double number_cell(const TextField& cell, const std::string& path, std::size_t line) {
  double value = 0.0;
  const auto parsed = std::from_chars(cell.text.data(), cell.text.data() + cell.text.size(), value);
  if (cell.text.empty() || parsed.ec != std::errc() || parsed.ptr != cell.text.data() + cell.text.size()) {
    throw Error(SourceLocation{path, line, cell.column}, fmt::format("'{}' is not a number", cell.text));
  }
  return value;
}

}  // namespace

namespace thermal {

ThermalRecord read_record(const ProcedureCall& call, const TemperatureModelOptions& options,
                          const std::vector<std::string>& temperature_columns) {
  const std::string& path = call.files.at("record");
  ThermalRecord record = read_thermal_record(path, options.time_column, options.output_column, temperature_columns);
  if (call.pulse_counts) {
    with_file_context(path, [&] { pulse_counts_as_rates(record.output, mean_sample_rate_hz(record.time_s)); });
  }
  return record;
}

std::optional<std::string> gap_warning(const ThermalRecord& record, double interval_s) {
  const TimeGaps found = find_time_gaps(record.time_s, {}, {});
  if (found.gaps.empty()) return std::nullopt;
  std::size_t missing = 0;
  for (const TimeGap& gap : found.gaps) missing += gap.missing;
  const TimeGap& longest = *std::max_element(found.gaps.begin(), found.gaps.end(), [](const auto& a, const auto& b) {
    return a.time_after - a.time_before < b.time_after - b.time_before;
  });
  return fmt::format(
      "{} gap(s) in the time stamps, {} sample(s) of {:.6g} s missing in all, the longest from {:.6g} s "
      "to {:.6g} s: the {} s intervals about them hold fewer samples (those a gap spans are missing) "
      "and are weighed as full ones",
      found.gaps.size(), missing, found.sample_interval, longest.time_before, longest.time_after, interval_s);
}

std::vector<Interval> intervals_of(const ThermalRecord& record, double interval_s, double scale_factor) {
  const std::size_t sensors = record.temperature_degC.size();
  std::vector<Interval> intervals;
  const double start = record.time_s.front();
  std::size_t i = 0;
  while (i < record.time_s.size()) {
    const double index = std::floor((record.time_s[i] - start) / interval_s);
    Interval interval;
    interval.temperature_degC.assign(sensors, 0.0);
    std::size_t count = 0;
    double time = 0.0, output = 0.0;
    for (; i < record.time_s.size() && std::floor((record.time_s[i] - start) / interval_s) == index; ++i, ++count) {
      time += record.time_s[i];
      output += record.output[i];
      for (std::size_t s = 0; s < sensors; ++s) interval.temperature_degC[s] += record.temperature_degC[s][i];
    }
    interval.time_s = time / static_cast<double>(count);
    // Bias in input-equivalent units: output / K (deg/s), in deg/h (GJB 2426A eq. 19).
    interval.bias_deg_h = output / static_cast<double>(count) / scale_factor * kSecondsPerHour;
    for (double& t : interval.temperature_degC) t /= static_cast<double>(count);
    intervals.push_back(std::move(interval));
  }
  return intervals;
}

void set_rates(std::vector<Interval>& intervals, std::size_t sensor, double rate_window_s, double soak_rate_degC_per_min) {
  std::vector<double> time, temperature;
  for (const auto& interval : intervals) {
    time.push_back(interval.time_s);
    temperature.push_back(interval.temperature_degC[sensor]);
  }
  const std::vector<double> rate = smoothed_rate_degC_per_min(time, temperature, rate_window_s);
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    intervals[i].rate_degC_per_min = rate[i];
    intervals[i].leg = rate[i] > soak_rate_degC_per_min ? 1 : rate[i] < -soak_rate_degC_per_min ? -1 : 0;
  }
}

double compensated_bias(const Interval& interval, std::size_t sensor, std::span<const ThermalCoefficient> coefficients,
                        double reference_temperature_degC) {
  return interval.bias_deg_h - thermal_bias_deg_h(coefficients, reference_temperature_degC,
                                                  interval.temperature_degC[sensor], interval.rate_degC_per_min,
                                                  interval.leg);
}

}  // namespace thermal

void TemperatureModelOptions::validate() const {
  if (!(scale_factor != 0.0 && std::isfinite(scale_factor))) throw ParameterError("scale_factor", "scale_factor must be non-zero");
  if (!(interval_s > 0.0)) throw ParameterError("interval_s", "interval_s must be positive");
  if (!(rate_window_s >= 2.0 * interval_s)) {
    throw ParameterError("rate_window_s", "rate_window_s must cover at least two intervals (2 x interval_s)");
  }
  if (!std::isfinite(reference_temperature_degC)) {
    throw ParameterError("reference_temperature", "reference_temperature must be finite");
  }
  if (!(soak_rate_degC_per_min >= 0.0)) throw ParameterError("soak_rate", "soak_rate must not be negative");
  if (!(stability_window_s >= interval_s)) {
    throw ParameterError("stability_window_s", "stability_window_s must be at least interval_s");
  }
  if (folds < 2) throw ParameterError("folds", "folds must be at least 2");
  if (maximum_order > kHighestOrder) {
    throw ParameterError("maximum_order", fmt::format("maximum_order must be at most {}", kHighestOrder));
  }
}

std::vector<double> smoothed_rate_degC_per_min(std::span<const double> time_s, std::span<const double> temperature_degC,
                                               double window_s) {
  const std::size_t n = time_s.size();
  std::vector<double> rate(n, 0.0);
  std::size_t first = 0, last = 0;  // the window [first, last)
  for (std::size_t i = 0; i < n; ++i) {
    while (time_s[first] < time_s[i] - 0.5 * window_s) ++first;
    while (last < n && time_s[last] <= time_s[i] + 0.5 * window_s) ++last;
    // The least-squares slope on centred sums: Σ(t − t̄)(T − T̄) / Σ(t − t̄)².
    const double count = static_cast<double>(last - first);
    double t_mean = 0.0, y_mean = 0.0;
    for (std::size_t k = first; k < last; ++k) {
      t_mean += time_s[k];
      y_mean += temperature_degC[k];
    }
    t_mean /= count;
    y_mean /= count;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t k = first; k < last; ++k) {
      sxy += (time_s[k] - t_mean) * (temperature_degC[k] - y_mean);
      sxx += (time_s[k] - t_mean) * (time_s[k] - t_mean);
    }
    rate[i] = sxx > 0.0 ? sxy / sxx * kSecondsPerMinute : 0.0;
  }
  return rate;
}

double thermal_bias_deg_h(std::span<const ThermalCoefficient> coefficients, double reference_temperature_degC,
                          double temperature_degC, double rate_degC_per_min, int leg) {
  const double dt = temperature_degC - reference_temperature_degC;
  double bias = 0.0;
  for (const ThermalCoefficient& c : coefficients) {
    const std::optional<TermOfCoefficient> term = term_of(c.name);
    if (!term) throw Error(fmt::format("unknown temperature model coefficient '{}'", c.name));
    const double value = c.value.value;
    switch (term->term) {
      case ThermalTerm::power:
        bias += value * std::pow(dt, static_cast<double>(term->power));
        break;
      case ThermalTerm::rate:
        bias += value * rate_degC_per_min;
        break;
      case ThermalTerm::temperature_rate:
        bias += value * dt * rate_degC_per_min;
        break;
      case ThermalTerm::hysteresis:
        bias += value * 0.5 * leg;
        break;
    }
  }
  return bias;
}

TemperatureModelResult temperature_model(const ThermalRecord& record, const TemperatureModelOptions& options) {
  options.validate();
  const std::size_t sensors = record.temperature_degC.size();
  if (sensors == 0) throw Error("no temperature sensor given");
  for (std::size_t s = 0; s < sensors; ++s) {
    if (record.temperature_degC[s].size() != record.time_s.size()) {
      throw Error(fmt::format("temperature sensor '{}' has {} samples, the time {}", record.sensor_names[s],
                              record.temperature_degC[s].size(), record.time_s.size()));
    }
  }
  if (record.output.size() != record.time_s.size() || record.time_s.empty()) {
    throw Error("the output and the time must have the same, non-zero number of samples");
  }
  constexpr std::size_t chosen_sensor = 0;  // the first sensor compensates; the others are compared
  // A model in temperature needs the temperature to vary: at one temperature D_0 would be the bias at
  // that temperature, presented as the bias at T_ref.
  if (is_constant(record.temperature_degC[chosen_sensor])) {
    throw Error(fmt::format("temperature sensor '{}' reads {} degC throughout the record: a temperature model needs "
                            "the temperature to vary (ramps between soaks)",
                            record.sensor_names[chosen_sensor], record.temperature_degC[chosen_sensor].front()));
  }
  std::vector<thermal::Interval> base = thermal::intervals_of(record, options.interval_s, options.scale_factor);
  const std::size_t per_window = window_intervals(options.stability_window_s, options.interval_s);
  if (base.size() < std::max(options.folds * (options.maximum_order + 5), 2 * per_window)) {
    throw Error(fmt::format("the record gives {} intervals of {} s: too few for {} folds of a model of order {} and "
                            "two stability windows",
                            base.size(), options.interval_s, options.folds, options.maximum_order));
  }
  TemperatureModelResult result;
  if (std::optional<std::string> gaps = thermal::gap_warning(record, options.interval_s)) {
    result.warnings.push_back(std::move(*gaps));
  }
  // D_0 is the bias at T_ref: outside the temperatures the record holds, it is an extrapolation.
  const auto [coldest, hottest] = std::minmax_element(record.temperature_degC[chosen_sensor].begin(),
                                                      record.temperature_degC[chosen_sensor].end());
  if (options.reference_temperature_degC < *coldest || options.reference_temperature_degC > *hottest) {
    result.warnings.push_back(fmt::format("the reference temperature {} degC lies outside the record's {:.4g} to {:.4g} "
                                          "degC: D_0 and the coefficients about it are extrapolated",
                                          options.reference_temperature_degC, *coldest, *hottest));
  }
  std::optional<SensorModel> chosen;
  std::vector<thermal::Interval> chosen_intervals;
  for (std::size_t s = 0; s < sensors; ++s) {
    std::vector<thermal::Interval> intervals = base;
    thermal::set_rates(intervals, s, options.rate_window_s, options.soak_rate_degC_per_min);
    const bool heating = std::any_of(intervals.begin(), intervals.end(), [](const auto& i) { return i.leg > 0; });
    const bool cooling = std::any_of(intervals.begin(), intervals.end(), [](const auto& i) { return i.leg < 0; });
    SensorModel model = fit_sensor(intervals, s, heating && cooling, options);
    const double dof = static_cast<double>(model.fit.degrees_of_freedom);
    const double rms = model.fit.residual_rms;
    result.sensors.push_back({record.sensor_names[s], model.design.order,
                              {rms, "deg/h", rms / std::sqrt(2.0 * std::max(dof, 1.0))}});
    if (s == 0) {
      if (!(heating && cooling)) {
        result.warnings.push_back("the record does not both heat and cool: no hysteresis D_H is fitted");
      }
      chosen = std::move(model);
      chosen_intervals = std::move(intervals);
    } else if (rms + 2.0 * result.sensors.back().residual_rms.uncertainty.value_or(0.0) < chosen->fit.residual_rms) {
      result.warnings.push_back(fmt::format("sensor '{}' fits with a residual rms of {:.3g} deg/h, below the "
                                            "compensation sensor '{}' ({:.3g} deg/h) by more than 2 sigma",
                                            record.sensor_names[s], rms, record.sensor_names[0],
                                            chosen->fit.residual_rms));
    }
  }
  const Design& design = chosen->design;
  const double reference = options.reference_temperature_degC;
  const Matrix m = design.physical_map(reference);
  const std::size_t n = design.columns();
  const std::vector<double> theta = predict(m, chosen->fit.parameters);
  Matrix covariance(n, n);  // M C Mᵀ
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t l = 0; l < n; ++l) sum += m(i, k) * chosen->fit.covariance(k, l) * m(j, l);
      }
      covariance(i, j) = sum;
    }
  }
  const std::vector<std::string> names = design.names();
  const std::vector<std::string> units = design.units();
  for (std::size_t i = 0; i < n; ++i) {
    result.coefficients.push_back({names[i], {theta[i], units[i], std::sqrt(covariance(i, i))}});
  }
  result.sensor = record.sensor_names[chosen_sensor];
  result.order = design.order;
  result.order_scores = chosen->scores;
  result.reference_temperature = {reference, "degC", std::nullopt};

  std::vector<double> raw, residual;
  for (thermal::Interval& interval : chosen_intervals) {
    raw.push_back(interval.bias_deg_h);
    residual.push_back(thermal::compensated_bias(interval, chosen_sensor, result.coefficients, reference));
  }
  result.raw_bias_stability = window_stability(raw, per_window);
  result.residual_bias_stability = window_stability(residual, per_window);
  const double rms = chosen->fit.residual_rms;
  result.residual_rms = {rms, "deg/h", rms / std::sqrt(2.0 * static_cast<double>(chosen->fit.degrees_of_freedom))};

  // GJB 2426A eq. (22) on the model's static part: |B(T) − B(T_ref)| / |T − T_ref| = |Σ_k D_Tk ΔT^(k−1)|
  // at the record's extremes, its variance gᵀ Cov g with g_k = ±ΔT^(k−1).
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const auto& interval : chosen_intervals) {
    low = std::min(low, interval.temperature_degC[chosen_sensor]);
    high = std::max(high, interval.temperature_degC[chosen_sensor]);
  }
  result.bias_temperature_sensitivity = {0.0, "deg/h/degC", 0.0};
  for (const double t : {low, high}) {
    std::vector<double> g(n, 0.0);
    double value = 0.0;
    for (std::size_t k = 1; k <= design.order; ++k) {
      g[k] = std::pow(t - reference, static_cast<double>(k - 1));
      value += theta[k] * g[k];
    }
    if (design.order == 0 || std::abs(value) < result.bias_temperature_sensitivity.value) continue;
    double variance = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) variance += g[i] * covariance(i, j) * g[j];
    }
    result.bias_temperature_sensitivity = {std::abs(value), "deg/h/degC", std::sqrt(variance)};
  }
  if (design.order == 0) {
    // Cross-validation chose no temperature term: the record does not resolve the bias's temperature
    // dependence at its noise, which is not a sensitivity of 0 (it was reported as 0 +- 0). The figure is
    // eq. (22) of the order-1 fit on the same intervals, |D_T| with its 1-sigma, and a warning says so.
    Design linear = design;
    linear.order = 1;
    LeastSquaresOptions strict;
    strict.parameter_names = linear.names();
    strict.serially_correlated = true;
    const LeastSquaresResult fit =
        solve_least_squares(linear.matrix(chosen_intervals, chosen_sensor), biases(chosen_intervals), strict);
    const Matrix map = linear.physical_map(reference);
    double slope = 0.0, variance = 0.0;  // D_T = row 1 of M times beta, its variance M_1 C M_1^T
    for (std::size_t k = 0; k < linear.columns(); ++k) {
      slope += map(1, k) * fit.parameters[k];
      for (std::size_t l = 0; l < linear.columns(); ++l) variance += map(1, k) * fit.covariance(k, l) * map(1, l);
    }
    const double sigma = std::sqrt(std::max(variance, 0.0));
    result.bias_temperature_sensitivity = {std::abs(slope), "deg/h/degC", sigma};
    result.warnings.push_back(fmt::format(
        "cross-validation chose order 0: the record does not resolve how the bias changes with temperature; the "
        "bias temperature sensitivity {:.3g} +- {:.3g} deg/h/degC is the order-1 fit's |D_T|{}",
        std::abs(slope), sigma,
        std::abs(slope) <= 2.0 * sigma ? fmt::format(", within 2 sigma of 0 (below {:.3g} at 2 sigma)", std::abs(slope) + 2.0 * sigma)
                                       : ""));
  }
  for (std::size_t i = 0; i < chosen_intervals.size(); ++i) {
    const thermal::Interval& interval = chosen_intervals[i];
    result.intervals.push_back({interval.time_s, interval.temperature_degC[chosen_sensor], interval.rate_degC_per_min,
                                interval.leg, interval.bias_deg_h, interval.bias_deg_h - residual[i]});
  }
  if (is_constant(record.output)) result.warnings.push_back("the output is constant: a stuck channel or a wrong column");
  return result;
}

TemperatureApplyResult apply_thermal_compensation(const ThermalRecord& record, const ThermalCompensation& compensation,
                                                  const TemperatureModelOptions& options) {
  options.validate();
  std::vector<thermal::Interval> intervals = thermal::intervals_of(record, options.interval_s, options.scale_factor);
  if (intervals.size() < 2 * window_intervals(options.stability_window_s, options.interval_s)) {
    throw Error(fmt::format("the record gives {} intervals of {} s: fewer than two stability windows", intervals.size(),
                            options.interval_s));
  }
  thermal::set_rates(intervals, 0, compensation.rate_window_s, compensation.soak_rate_degC_per_min);
  TemperatureApplyResult result;
  if (std::optional<std::string> gaps = thermal::gap_warning(record, options.interval_s)) {
    result.warnings.push_back(std::move(*gaps));
  }
  // The coefficients are in deg/h: a record read with another K has its bias in another scale (fitted
  // with K = 1 and applied with 36000, the stability after compensation read 2983 deg/h for 0.083).
  if (compensation.scale_factor &&
      std::abs(options.scale_factor - *compensation.scale_factor) > 1e-6 * std::abs(*compensation.scale_factor)) {
    result.warnings.push_back(
        fmt::format("the coefficients were fitted with a scale factor K of {:.10g}, and are applied with {:.10g} "
                    "(output units per deg/s): the bias is read in another scale",
                    *compensation.scale_factor, options.scale_factor));
  }
  result.sensor = record.sensor_names.front();
  std::vector<double> raw, residual;
  for (const thermal::Interval& interval : intervals) {
    raw.push_back(interval.bias_deg_h);
    residual.push_back(thermal::compensated_bias(interval, 0, compensation.coefficients,
                                                 compensation.reference_temperature_degC));
    result.intervals.push_back({interval.time_s, interval.temperature_degC[0], interval.rate_degC_per_min, interval.leg,
                                interval.bias_deg_h, interval.bias_deg_h - residual.back()});
  }
  const std::size_t per_window = window_intervals(options.stability_window_s, options.interval_s);
  result.raw_bias_stability = window_stability(raw, per_window);
  result.residual_bias_stability = window_stability(residual, per_window);
  const double count = static_cast<double>(residual.size());
  const double sd = sample_standard_deviation(residual);
  result.residual_rms = {sd, "deg/h", sd / std::sqrt(2.0 * (count - 1.0))};
  // The mean's 1-sigma allows a drift correlated from interval to interval, as the model's fit
  // does (sd / sqrt(n) takes the intervals as independent). The model's own uncertainty is not in
  // it: the export holds each coefficient's, not their covariance.
  Matrix ones(residual.size(), 1);
  for (std::size_t i = 0; i < residual.size(); ++i) ones(i, 0) = 1.0;
  LeastSquaresOptions correlated;
  correlated.serially_correlated = true;
  const LeastSquaresResult level = solve_least_squares(ones, residual, correlated);
  result.residual_mean = {mean(residual), "deg/h", level.standard_error(0)};
  return result;
}

std::string thermal_coefficients_text(const TemperatureModelResult& result, const TemperatureModelOptions& options,
                                      const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".json") {
    nlohmann::json coefficients = nlohmann::json::object();
    for (const auto& c : result.coefficients) coefficients[c.name] = c.value;
    return json_text(nlohmann::json{{"model", "inertest temperature model"},
                                    {"sensor", result.sensor},
                                    {"order", result.order},
                                    {"scale_factor", options.scale_factor},
                                    {"reference_temperature_degC", options.reference_temperature_degC},
                                    {"rate_window_s", options.rate_window_s},
                                    {"soak_rate_degC_per_min", options.soak_rate_degC_per_min},
                                    {"coefficients", coefficients}},
                     2) +
           "\n";
  }
  if (extension != ".csv") throw Error(fmt::format("{}: the export is .json or .csv, not '{}'", path, extension));
  std::string text = fmt::format(
      "name,value,unit,uncertainty\nsensor,{},,\norder,{},,\nreference_temperature,{},degC,\n"
      "rate_window,{},s,\nsoak_rate,{},degC/min,\nscale_factor,{},,\n",
      result.sensor, result.order, options.reference_temperature_degC, options.rate_window_s,
      options.soak_rate_degC_per_min, options.scale_factor);
  for (const auto& c : result.coefficients) {
    text += fmt::format("{},{},{},{}\n", c.name, c.value.value, c.value.unit, c.value.uncertainty.value_or(0.0));
  }
  return text;
}

ThermalCompensation read_thermal_compensation(const std::string& path) {
  const MappedFile file(path);
  const std::string_view text = file.text();
  ThermalCompensation compensation;
  const SourceLocation file_location{path, 0, 0};
  std::optional<std::size_t> order;  // stated by exports since the order was written; else inferred
  auto set_order = [&](double value, const SourceLocation& where) {
    if (!(value >= 0.0 && value <= static_cast<double>(kHighestOrder) && value == std::floor(value))) {
      throw Error(where, fmt::format("order: {} is not a whole number from 0 to {}", value, kHighestOrder));
    }
    order = static_cast<std::size_t>(value);
  };
  if (std::filesystem::path(path).extension() == ".json") {
    try {
      const nlohmann::json json = nlohmann::json::parse(text);
      compensation.sensor = json.at("sensor").get<std::string>();
      if (json.contains("order")) set_order(json.at("order").get<double>(), file_location);
      if (json.contains("scale_factor")) compensation.scale_factor = json.at("scale_factor").get<double>();
      compensation.reference_temperature_degC = json.at("reference_temperature_degC").get<double>();
      compensation.rate_window_s = json.at("rate_window_s").get<double>();
      compensation.soak_rate_degC_per_min = json.at("soak_rate_degC_per_min").get<double>();
      for (const auto& [name, figure] : json.at("coefficients").items()) {
        compensation.coefficients.push_back(
            checked_coefficient(name, figure.get<Figure>(), file_location, file_location, "coefficients." + name));
      }
    } catch (const nlohmann::json::exception& e) {
      throw Error(file_location, fmt::format("not an exported temperature model: {}", e.what()));
    }
    if (compensation.coefficients.empty()) throw Error(file_location, "no coefficients");
    check_complete_model(compensation.coefficients, order, file_location);
    return compensation;
  }
  io_detail::LineCursor cursor(text);
  std::size_t line_number = 0;  // of the last line read, for the message of a file without coefficients
  for (io_detail::Line row{}; cursor.next(row);) {
    const std::string_view line = row.text;
    line_number = row.number;
    if (line.empty() || line_number == 1) continue;
    const std::vector<TextField> cells = split_text_line(line, ',', path, line_number);
    if (cells.size() != 4) throw Error(SourceLocation{path, line_number, 1}, "expected name,value,unit,uncertainty");
    const std::string& name = cells[0].text;
    if (name == "sensor") {
      compensation.sensor = cells[1].text;
      continue;
    }
    const double value = number_cell(cells[1], path, line_number);
    // A setting in the unit its row states (as the D_ rows; none: the export's): 293.15 K is 20 degC,
    // 2 min is 120 s; a unit not of its kind is an error at its cell (it was read as degC, s or
    // degC/min, whatever it said).
    const auto in_unit = [&](const char* unit) {
      const std::string& stated = cells[2].text;
      if (stated.empty()) return value;  // a file written by hand without units: the export's
      try {
        if (std::string_view(unit) == "degC" && stated == "K") return value + constants::kAbsoluteZeroDegC;  // absolute
        return convert(value, stated, unit);
      } catch (const Error& e) {
        throw Error(SourceLocation{path, line_number, cells[2].column}, fmt::format("{}: {}", name, e.message()));
      }
    };
    if (name == "reference_temperature") {
      compensation.reference_temperature_degC = in_unit("degC");
    } else if (name == "rate_window") {
      compensation.rate_window_s = in_unit("s");
    } else if (name == "soak_rate") {
      compensation.soak_rate_degC_per_min = in_unit("degC/min");
    } else if (name == "order") {
      set_order(value, SourceLocation{path, line_number, cells[1].column});
    } else if (name == "scale_factor") {
      compensation.scale_factor = value;
    } else if (name.starts_with("D_")) {
      const SourceLocation where{path, line_number, 1};
      const bool repeated = std::any_of(compensation.coefficients.begin(), compensation.coefficients.end(),
                                        [&](const ThermalCoefficient& c) { return c.name == name; });
      if (repeated) throw Error(where, fmt::format("coefficient '{}' is given twice", name));
      compensation.coefficients.push_back(checked_coefficient(
          name, {value, cells[2].text, number_cell(cells[3], path, line_number)}, where,
          SourceLocation{path, line_number, cells[2].column}, "coefficient " + name));
    } else {
      throw Error(SourceLocation{path, line_number, 1}, fmt::format("unknown row '{}'", name));
    }
  }
  if (compensation.coefficients.empty()) throw Error(SourceLocation{path, line_number, 0}, "no coefficients");
  check_complete_model(compensation.coefficients, order, SourceLocation{path, 0, 0});
  return compensation;
}

namespace {

// The offset that takes a temperature column to degC by the unit its name states after a '_' or in
// brackets ("coil_K", "chamber [K]", "coil (kelvin)": -273.15; "coil_degC", "T [°C]", a sensor's name "T_1" or
// "coil_top": 0). A temperature in kelvin read as degC put T_ref at 20 K and D_0 100 times off.
double offset_to_degC(const std::string& name) {
  const std::size_t cut = name.find_last_of("_[(");
  if (cut == std::string::npos) return 0.0;
  std::string unit = name.substr(cut + 1);
  while (!unit.empty() && (unit.back() == ']' || unit.back() == ')' || unit.back() == ' ')) unit.pop_back();
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  return unit == "K" || unit == "kelvin" || unit == "Kelvin" ? constants::kAbsoluteZeroDegC : 0.0;
}

}  // namespace

ThermalRecord read_thermal_record(const std::string& path, const std::string& time_column,
                                  const std::string& output_column, const std::vector<std::string>& temperature_columns) {
  TextTableOptions table_options;
  table_options.columns = {ColumnSelector::parse(time_column), ColumnSelector::parse(output_column)};
  for (const std::string& column : temperature_columns) table_options.columns.push_back(ColumnSelector::parse(column));
  TextTable table = read_text_table(path, table_options);
  ThermalRecord record;
  record.time_s = take_time_column_s(table, 0);
  record.output = std::move(table.columns[1]);
  for (std::size_t s = 0; s < temperature_columns.size(); ++s) {
    if (const double offset = offset_to_degC(table.names[s + 2]); offset != 0.0) {
      for (double& t : table.columns[s + 2]) t += offset;
    }
    // A sensor's fault code (-999) or a typo is no temperature: it bent the model silently.
    const std::vector<double>& temperatures = table.columns[s + 2];
    for (std::size_t i = 0; i < temperatures.size(); ++i) {
      if (temperatures[i] < constants::kAbsoluteZeroDegC) {
        throw Error(locate_cell(table, i, s + 2), fmt::format("{} degC is below absolute zero", temperatures[i]));
      }
      // A column in kelvin not named so (its D_0 came out 33 deg/h for 1, with no word).
      if (temperatures[i] > kHottestTestDegC) {
        throw Error(locate_cell(table, i, s + 2),
                    fmt::format("{} degC is above {} degC: is the column in kelvin? name it with its unit ({}_K, "
                                "\"{} [K]\")",
                                temperatures[i], kHottestTestDegC, table.names[s + 2], table.names[s + 2]));
      }
    }
    record.sensor_names.push_back(table.names[s + 2].empty() ? temperature_columns[s] : table.names[s + 2]);
    record.temperature_degC.push_back(std::move(table.columns[s + 2]));
  }
  return record;
}

}  // namespace inertest
