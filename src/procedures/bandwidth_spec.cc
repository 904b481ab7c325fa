// The bandwidth and output delay procedure's one description (issue 22): the CLI command
// `inertest bandwidth`, the plan kind "bandwidth", its JSON and its text report are all generated
// from it.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/units.h"
#include "inertest/io/output_record.h"
#include "inertest/io/procedure_inputs.h"
#include "inertest/procedures/bandwidth_and_delay.h"

namespace inertest {
namespace {

// The sine fits of the raw records (5.13.4, eqs. 32-34); null for a table of gains.
nlohmann::json vibration_fits_of(const BandwidthResult& result) {
  if (result.vibration_fits.empty()) return nullptr;
  nlohmann::json fits = nlohmann::json::array();
  const std::string rate_unit = result.angle_unit + "/s";
  for (const auto& f : result.vibration_fits) {
    fits.push_back({
        {"frequency_hz", f.frequency_hz},
        {"output_amplitude", Figure{f.output.amplitude, result.output_unit, f.output.amplitude_standard_error}},
        {"output_phase",
         Figure{f.output.phase / constants::kDegree, "deg", f.output.phase_standard_error / constants::kDegree}},
        {"angle_amplitude", Figure{f.angle.amplitude, result.angle_unit, f.angle.amplitude_standard_error}},
        {"angle_phase",
         Figure{f.angle.phase / constants::kDegree, "deg", f.angle.phase_standard_error / constants::kDegree}},
        {"rate_amplitude", Figure{f.rate_amplitude, rate_unit, std::nullopt}},
    });
  }
  return fits;
}

// F_L / R_L with the polarity's sign (eq. 35's reference gain); null for a table of gains.
nlohmann::json gain_at_lowest_frequency_of(const BandwidthResult& result) {
  if (result.vibration_fits.empty()) return nullptr;
  const auto& lowest = result.vibration_fits.front();
  return Figure{static_cast<double>(result.polarity) * lowest.output.amplitude / lowest.rate_amplitude,
                result.output_unit + "/(" + result.angle_unit + "/s)", std::nullopt};
}

// The columns of the raw records (time, gyro output, interferometer angle) and the procedure's options.
struct BandwidthInputOptions {
  std::string time_column = "time_s";
  std::string output_column = "output";
  std::string angle_column = "angle_deg";
  BandwidthOptions bandwidth;
};

}  // namespace

ProcedureSpec bandwidth_spec() {
  using Options = BandwidthInputOptions;
  return ProcedureDefinition<Options, BandwidthResult>(
             "bandwidth", "Bandwidth and output delay", "GJB 2426A-2004 5.13-5.14, eqs. (32)-(46)",
             "Bandwidth (5.13, eqs. 32-41) and output delay (5.14, eqs. 42-46) from angular-vibration runs,\n"
             "model G(s) = K/(T s + 1) e^(-Td s), Bw = 1/(2 pi T).\n"
             "GAINS is a CSV with the header 'freq_hz,gain,phase_deg': one row per vibration frequency\n"
             "(Hz, positive, increasing), the gain Gi = Fi/FL (eq. 35) and the phase of the gyro output\n"
             "against the input RATE in deg (negative for a lag), in any turn (+-180, 0 to -360, unwrapped):\n"
             "the lag is taken to grow from each frequency to the next (by less than 300 deg).\n"
             "--records RUNS instead: RUNS is a CSV with the header 'freq_hz,file', one record per frequency\n"
             "(paths relative to RUNS). Each record has the columns --time-column (s), --output-column\n"
             "(gyro output) and --angle-column (interferometer angle, --angle-unit); both are sine-fitted at\n"
             "the frequency. Gi = (Fi/Ri)/(FL/RL), Ri the rate amplitude, L the lowest frequency; the phase\n"
             "is the output's against the rate (the angle's phase + 90 deg).\n"
             "At least --minimum-frequencies (default 10, 5.13.3 a) frequencies. A phase beyond +-90 deg at the\n"
             "lowest frequency is a negative scale factor: 180 deg is removed from every phase before the delay\n"
             "fit (polarity -1).")
      .chinese_title("频带宽度与输出延迟时间")
      .report_method(
          "Sinusoidal rate inputs at logarithmically spaced frequencies; the gains fit the first-order model "
          "G² = K² − G²·ω²·T² and the bandwidth is 1/(2πT); the phases give the output delay (a negative scale "
          "factor's 180° removed first).",
          "在按对数分布的各频率点施加正弦角速度输入；由各频率增益按一阶模型 G² = K² − G²ω²T² 拟合，带宽为 "
          "1/(2πT)；由相位求输出延迟时间（标度因数为负时先去除其 180° 相移）。")
      .input(InputSpec("gains", "CSV of gains and phases (freq_hz,gain,phase_deg)")
                 .read_from_file("GAINS", "file")
                 .alternative_in("data"))
      .input(InputSpec("records", "a raw record per frequency (time, gyro output, interferometer angle), increasing")
                 .numbered_runs("frequency_hz", "10:vib_10Hz.csv")
                 .listed_on_command_line("--records", "freq_hz")
                 .holds_raw_samples()
                 .alternative_in("data"))
      .parameter(ParameterSpec("time_column", "time column of the records (s)"), &Options::time_column)
      .parameter(ParameterSpec("output_column", "gyro output column of the records"), &Options::output_column)
      .parameter(ParameterSpec("angle_column", "interferometer angle column of the records"), &Options::angle_column)
      .parameter(ParameterSpec("angle_unit", "unit of the angle column"), &Options::bandwidth,
                 &BandwidthOptions::angle_unit)
      .parameter(ParameterSpec("output_unit", "instrument output unit").instrument_gives("output_unit", true),
                 &Options::bandwidth, &BandwidthOptions::output_unit)
      .parameter(ParameterSpec("minimum_frequencies", "fewest frequencies accepted (5.13.3 a: 10; no less than 3)"),
                 &Options::bandwidth, &BandwidthOptions::minimum_frequencies)
      .field({"bandwidth", FieldRole::headline, "bandwidth Bw", "带宽", "eqs. (37)-(41)"}, &BandwidthResult::bandwidth)
      .field({"delay", FieldRole::headline, "output delay Td", "输出延迟时间", "eqs. (43)-(46)"},
             &BandwidthResult::delay)
      .field({"dc_gain", FieldRole::detail, "dc gain K", "静态增益 K", "eq. (40)"}, &BandwidthResult::dc_gain)
      .field({"time_constant", FieldRole::detail, "time constant T", "时间常数", "eq. (38)"},
             &BandwidthResult::time_constant)
      .field({"gain_fit_residual_rms", FieldRole::detail, "gain fit residual rms", "增益拟合残差均方根", "eq. (37)"},
             &BandwidthResult::gain_fit_residual_rms)
      .field({"phase_fit_residual_rms", FieldRole::detail, "phase fit residual rms", "相位拟合残差均方根", "eq. (44)"},
             &BandwidthResult::phase_fit_residual_rms)
      .field({"polarity",
              FieldRole::detail,
              "output polarity",
              "极性",
              "eq. (43)",
              {},
              {{"1", "positive"}, {"-1", "negative: 180 deg removed from every phase before eqs. (43)-(46)"}}},
             &BandwidthResult::polarity)
      .field_from({"bode",
                   FieldRole::curve,
                   "Bode data",
                   "伯德图数据",
                   "eqs. (35), (42)-(46)",
                   {"frequency_hz", "gain", "fitted_gain", "phase_deg", "fitted_phase_deg"}},
                  [](const BandwidthResult& result) {
                    nlohmann::json bode = nlohmann::json::array();
                    for (const auto& p : result.bode) {
                      bode.push_back({{"frequency_hz", p.frequency_hz},
                                      {"gain", p.gain},
                                      {"fitted_gain", p.fitted_gain},
                                      {"phase_deg", p.phase_deg},
                                      {"fitted_phase_deg", p.fitted_phase_deg}});
                    }
                    return bode;
                  })
      .field_from(
          {"vibration_fits", FieldRole::table, "sine fits of the records", "振动记录正弦拟合", "eqs. (32)-(34)"},
          vibration_fits_of)
      .field_from({"gain_at_lowest_frequency", FieldRole::detail, "gain at the lowest frequency FL/RL",
                   "最低频率点增益", "eq. (35)"},
                  gain_at_lowest_frequency_of)
      .field({"warnings", FieldRole::hidden, "warnings", "警告", ""}, &BandwidthResult::warnings)
      .checked_by([](const ProcedureCall& call, const Options& options) {
        options.bandwidth.validate();
        if (!call.runs.contains("records")) return;
        const std::vector<ListedFile> runs = listed_files(call.runs.at("records"));
        check_increasing_frequencies(runs);
        if (runs.size() < options.bandwidth.minimum_frequencies) {
          throw Error(fmt::format("names {} frequencies; GJB 2426A 5.13.3 a) asks for at least {}", runs.size(),
                                  options.bandwidth.minimum_frequencies));
        }
      })
      .unit_of("bandwidth", "Hz")
      .unit_of("delay", "s")
      .unit_of("dc_gain", "1")
      .unit_of("time_constant", "s")
      .unit_of("gain_fit_residual_rms", "1")
      .unit_of("phase_fit_residual_rms", "deg")
      .unit_of("gain_at_lowest_frequency", "{output_unit}/({angle_unit}/s)")
      .compute([](const ProcedureCall& call, const Options& options) {
        if (call.files.contains("gains")) {
          return bandwidth_and_delay(read_frequency_response(call.files.at("gains")), options.bandwidth);
        }
        auto records = read_angular_vibration_records(listed_files(call.runs.at("records")), options.time_column,
                                                      options.output_column, options.angle_column);
        if (call.pulse_counts) {
          for (AngularVibrationRecord& record : records) {
            with_file_context(record.source,
                              [&] { pulse_counts_as_rates(record.output, mean_sample_rate_hz(record.time_s)); });
          }
        }
        return bandwidth_and_delay(std::span<const AngularVibrationRecord>(records), options.bandwidth);
      });
}

}  // namespace inertest
