// Plan kind "allan": Allan variance and noise terms of a rate record (GJB 2426A-2004 5.12.5.4.2).
//   file = "static.f64"          # the record
//   format = "f64"               # auto (default: .mat, HDF5, TDMS by magic bytes, else csv), csv,
//                                # f64 or f32 (raw little-endian), mat, hdf5, tdms
//   column = "rate"              # optional: header name or 1-based index; channel "group/channel", "struct.field"
//   columns = ["gx", "gy", "gz", "ax", "ay", "az"]  # instead of column: every channel in one pass;
//                                # the result is {"channels": {"gx": {...}, ...}} (issue 19)
//   sample_rate_hz = 100         # optional: default the instrument's sample_rate_hz
//   input_unit = "deg/h"         # optional: unit of the samples; with columns also "deg/s,ax=m/s^2,..."
//   taus = "octave"              # optional: octave, decade, all, N/decade or "0.1,1,10"
//   scale_factor = 1.2e5         # optional: output units per deg/s; the raw output is divided by it
//                                # and converted to deg/h (input_unit must then be left out)
//   fit_range = [1.0, 1000.0]    # optional: the taus (s) of the eq. (30) fit, or "1:1000";
//                                # default: chosen automatically
//   psd = true                   # optional: also the Welch PSD, its noise terms and periodic components;
//   psd_window = "hann"          # implied by psd_window (hann, hamming, blackman-harris, rectangular)
//   psd_segment_length = 4096    # and psd_segment_length (default automatic)
// The result is the JSON of `inertest allan --json`.
#include <cmath>

#include "campaign/step_registry.h"
#include "inertest/allan/allan.h"
#include "inertest/allan/allan_channels.h"

namespace inertest::campaign {
namespace {

ColumnSelector column_of(PlanTable& step) {
  const toml::node* node = step.raw().get("column");
  if (node != nullptr && node->is_integer()) {
    const double index = step.number("column");
    if (!(index >= 1.0) || index != std::floor(index)) step.fail_at("column", "a column index is 1-based");
    ColumnSelector selector;
    selector.index = static_cast<std::size_t>(index);
    return selector;
  }
  return ColumnSelector::parse(step.string("column"));
}

StepAction prepare(PlanTable& step, const PlanContext& context) {
  RateRecordSource source;
  source.path = step.file("file");
  try {
    source.format = parse_rate_record_format(step.string_or("format", "auto"));
  } catch (const Error& e) {
    step.fail_at("format", e.message());
  }
  if (step.contains("column")) source.column = column_of(step);
  std::vector<ColumnSelector> columns;
  if (step.contains("columns")) {
    if (step.contains("column")) step.fail_at("columns", "column and columns exclude each other");
    for (const std::string& name : step.strings("columns")) columns.push_back(ColumnSelector::parse(name));
    if (columns.empty()) step.fail_at("columns", "name at least one channel");
  }
  AllanOptions options;
  const std::optional<double> rate = step.optional_number("sample_rate_hz");
  if (rate) {
    options.sample_rate_hz = *rate;
  } else if (context.instrument.sample_rate_hz) {
    options.sample_rate_hz = *context.instrument.sample_rate_hz;
  } else {
    step.fail("no sample rate: set sample_rate_hz here or in the instrument table");
  }
  const std::optional<std::string> unit = step.optional_string("input_unit");
  options.taus = step.string_or("taus", options.taus);
  if (const std::optional<double> scale_factor = step.optional_number("scale_factor")) {
    if (unit) step.fail_at("input_unit", "input_unit and scale_factor exclude each other: scaled output is in deg/h");
    if (!(*scale_factor != 0.0) || !std::isfinite(*scale_factor)) step.fail_at("scale_factor", "must be nonzero");
    // raw / (output per deg/s) = deg/s; times 3600 = deg/h.
    options.scale = 3600.0 / *scale_factor;
    options.input_unit = "deg/h";
  } else if (unit && columns.empty()) {
    options.input_unit = *unit;
  }
  if (step.contains("fit_range")) {
    try {
      const toml::node* node = step.raw().get("fit_range");
      if (node != nullptr && node->is_string()) {
        options.fit_range = parse_fit_range(step.string("fit_range"));
      } else {
        const std::vector<double> range = step.numbers("fit_range");
        if (range.size() != 2) step.fail_at("fit_range", "give [tau_min, tau_max] in s");
        options.fit_range = FitRange{range[0], range[1]};
      }
      options.validate();
    } catch (const Error& e) {
      if (e.location()) throw;
      step.fail_at("fit_range", e.message());
    }
  }
  if (step.boolean_or("psd", false) || step.contains("psd_window") || step.contains("psd_segment_length")) {
    WelchOptions welch;
    try {
      welch.window = parse_spectral_window(step.string_or("psd_window", "hann"));
    } catch (const Error& e) {
      step.fail_at("psd_window", e.message());
    }
    const double segment = step.number_or("psd_segment_length", 0.0);
    if (!(segment >= 0.0) || segment != std::floor(segment)) step.fail_at("psd_segment_length", "a whole number of samples");
    welch.segment_length = static_cast<std::size_t>(segment);
    options.psd = welch;
  }
  try {
    options.validate();
  } catch (const Error& e) {
    step.fail(e.message());
  }
  if (!columns.empty()) {
    return [source, columns, units = unit.value_or(""), options](const StepRunContext& run) {
      return allan_variance_of_channels_in_file(source, columns, units, options, run.progress).to_json();
    };
  }
  return [source, options](const StepRunContext& run) {
    return allan_variance_of_file(source, options, run.progress).to_json();
  };
}

const bool registered = register_step("allan", prepare);

}  // namespace
}  // namespace inertest::campaign
