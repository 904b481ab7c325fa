// centrifuge: calibration of a gyro's drift coefficients on a precision centrifuge with a
// counter-rotating platform (the centrifuge paper, cited in core/citations.h).
#include <fmt/format.h>

#include "bindings.h"
#include "inertest/centrifuge/centrifuge_model.h"
#include "inertest/centrifuge/centrifuge_record.h"
#include "inertest/centrifuge/drift_calibration.h"
#include "inertest/centrifuge/harmonic_analysis.h"

namespace inertest::python {
namespace {

using namespace inertest::centrifuge;

struct DriftCalibrationTag {};

std::string method_name(const HarmonicFit& fit) { return to_string(fit.method); }

std::string run_repr(const CentrifugeRun& run) {
  return fmt::format("CentrifugeRun(accel_g={}, beta_rad={}, amplitudes=[{}]{})", run.accel_g, run.beta_rad,
                     fmt::join(run.amplitudes, ", "),
                     run.omega_rad_s ? fmt::format(", omega_rad_s={}", *run.omega_rad_s) : std::string());
}

CentrifugeRun run_from_samples(double accel_g, double beta_rad, const DoubleArray& gamma_rad,
                               const DoubleArray& output, std::optional<double> omega_rad_s) {
  const auto gamma = as_span(gamma_rad, "gamma_rad");
  const auto outputs = as_span(output, "output");
  require_equal_lengths({{"gamma_rad", gamma.size()}, {"output", outputs.size()}});
  const HarmonicFit fit = analyse_harmonics(gamma, outputs);
  return CentrifugeRun{accel_g, omega_rad_s, beta_rad, fit.amplitudes, fit, {}};
}

CentrifugeSite site_of(double radius_m, std::optional<double> latitude_deg, double gravity_m_s2) {
  CentrifugeSite site;
  site.radius_m = radius_m;
  site.latitude_rad = latitude_deg.value_or(0.0) * constants::kDegree;
  site.gravity_m_s2 = gravity_m_s2;
  return site;
}

// As the CLI's centrifuge command: the latitude is required while compensating (the Earth rate
// enters epsilon); without compensation it defaults to 0 with a warning.
ResultOf<DriftCalibrationTag> calibrate(const std::vector<CentrifugeRun>& runs, std::optional<double> latitude_deg,
                                        double radius_m, double gravity_m_s2, std::optional<double> k1_rad,
                                        std::optional<double> k2_rad, std::optional<double> delta_omega_rad_s,
                                        bool compensation, bool estimate_errors, double rank_threshold) {
  DriftCalibrationOptions options;
  options.compensation = compensation;
  options.estimate_errors = estimate_errors;
  if (!latitude_deg && compensation) {
    throw Error("centrifuge: latitude_deg is required: the Earth rate at the site enters the compensation "
                "(or pass compensation=False)");
  }
  options.site = site_of(radius_m, latitude_deg, gravity_m_s2);
  options.k1_rad = k1_rad;
  options.k2_rad = k2_rad;
  options.delta_omega_rad_s = delta_omega_rad_s;
  options.rank_threshold = rank_threshold;
  options.validate();
  DriftCalibrationResult result = calibrate_drift_coefficients(runs, options);
  if (!latitude_deg) result.warnings.emplace_back("no latitude_deg: 0 deg in the Coriolis term");
  return make_spec_result<DriftCalibrationTag>(centrifuge_spec(), result);
}

py::array_t<double> model_output(const std::array<double, kDriftTermCount>& coefficients, double omega_rad_s,
                                 double beta_rad, const DoubleArray& gamma_rad, double radius_m, double latitude_deg,
                                 double gravity_m_s2, double k1_rad, double k2_rad, double delta_omega_rad_s) {
  const CentrifugeSite site = site_of(radius_m, latitude_deg, gravity_m_s2);
  site.validate();
  // A NaN among them made every output NaN, silently.
  for (std::size_t term = 0; term < kDriftTermCount; ++term) {
    if (!std::isfinite(coefficients[term])) {
      throw Error(fmt::format("coefficients: {} is not a finite number", drift_term_name(term)));
    }
  }
  for (const auto& [name, value] : {std::pair{"omega_rad_s", omega_rad_s}, {"beta_rad", beta_rad}, {"k1_rad", k1_rad},
                                    {"k2_rad", k2_rad}, {"delta_omega_rad_s", delta_omega_rad_s}}) {
    if (!std::isfinite(value)) throw Error(fmt::format("{} must be a finite number, got {}", name, value));
  }
  const CentrifugeErrors errors{k1_rad, k2_rad, delta_omega_rad_s};
  const auto gamma = as_span(gamma_rad, "gamma_rad");
  std::vector<double> output(gamma.size());
  for (std::size_t i = 0; i < gamma.size(); ++i) {
    output[i] = centrifuge_model_output(coefficients, site, errors, omega_rad_s, beta_rad, gamma[i]);
  }
  return to_numpy(std::move(output));
}

}  // namespace

void wrap_centrifuge(py::module_& module) {
  using namespace pybind11::literals;
  py::class_<HarmonicFit>(module, "HarmonicFit",
                          "The harmonic amplitudes of eq. (11) of the centrifuge paper, fitted to one run's samples.")
      .def_readonly("amplitudes", &HarmonicFit::amplitudes, "k0, k1c, k1s, k2c, k2s, in the unit of the outputs.")
      .def_readonly("residual_rms", &HarmonicFit::residual_rms, "rms of the samples about the five-term fit.")
      .def_readonly("sample_count", &HarmonicFit::sample_count)
      .def_readonly("revolutions", &HarmonicFit::revolutions, "platform revolutions covered by the samples")
      .def_property_readonly("method", &method_name, "'dft' (equally spaced whole revolutions) or 'least_squares'.");

  py::class_<CentrifugeRun>(module, "CentrifugeRun",
                            "One run on the centrifuge: a g-level, a platform angle beta and the five harmonic\n"
                            "amplitudes k0, k1c, k1s, k2c, k2s (deg/h) of the gyro output (paper eq. 11).")
      .def(py::init([](double accel_g, double beta_rad, const std::array<double, kHarmonicCount>& amplitudes,
                       std::optional<double> omega_rad_s) {
             return CentrifugeRun{accel_g, omega_rad_s, beta_rad, amplitudes, std::nullopt, {}};
           }),
           "accel_g"_a, "beta_rad"_a, "amplitudes"_a, "omega_rad_s"_a = py::none())
      .def_static("from_samples", &run_from_samples, "accel_g"_a, "beta_rad"_a, "gamma_rad"_a, "output"_a,
                  "omega_rad_s"_a = py::none(),
                  "A run from raw samples of the output (deg/h) at platform angles gamma (rad), by the harmonic\n"
                  "analysis of eq. (11): exact DFT bins for equally spaced whole revolutions, else least squares.\n"
                  "The arrays are read in place (no copy).")
      .def_readwrite("accel_g", &CentrifugeRun::accel_g, "nominal g-level; equal accel_g form one g-level")
      .def_readwrite("omega_rad_s", &CentrifugeRun::omega_rad_s,
                     "main-axis rate Omega (rad/s); None: sqrt(accel_g * g / R0)")
      .def_readwrite("beta_rad", &CentrifugeRun::beta_rad, "platform angle about axis C (rad)")
      .def_readwrite("amplitudes", &CentrifugeRun::amplitudes, "k0, k1c, k1s, k2c, k2s (deg/h)")
      .def_readonly("harmonic_fit", &CentrifugeRun::harmonic_fit, "the HarmonicFit when made from samples, else None")
      .def_property_readonly(
          "location", [](const CentrifugeRun& run) { return run.location.file.empty() ? std::string() : run.location.to_string(); },
          "where the run is in its input file ('' when not from a file)")
      .def("__repr__", &run_repr);

  py::class_<CentrifugeRecord>(module, "CentrifugeRecord",
                               "A centrifuge test record: harmonic amplitudes (one row per run) or raw samples.")
      .def_property_readonly("kind",
                             [](const CentrifugeRecord& record) {
                               return record.kind == CentrifugeRecord::Kind::kHarmonics ? "harmonics" : "samples";
                             })
      .def("runs", &CentrifugeRecord::runs,
           "The runs as harmonic amplitudes: as read, or by the harmonic analysis (eq. 11) of the samples.");
  module.def("read_centrifuge_record", [](const std::filesystem::path& path) { return read_centrifuge_record(path.string()); }, "path"_a,
             "Reads a centrifuge record as the CLI does: header accel_g,beta_deg,k0,k1c,k1s,k2c,k2s (harmonic\n"
             "amplitudes, deg/h) or accel_g,beta_deg,gamma_deg,output (raw samples, deg/h), either with an\n"
             "optional omega_rad_s column. Raises inertest.Error naming file and line.");
  module.def(
      "analyse_harmonics",
      [](const DoubleArray& gamma_rad, const DoubleArray& output) {
        const auto gamma = as_span(gamma_rad, "gamma_rad");
        const auto outputs = as_span(output, "output");
        require_equal_lengths({{"gamma_rad", gamma.size()}, {"output", outputs.size()}});
        return analyse_harmonics(gamma, outputs);
      },
      "gamma_rad"_a, "output"_a,
      "Fits w = k0 + k1c cos g + k1s sin g + k2c cos 2g + k2s sin 2g (centrifuge paper eq. 11) to samples at\n"
      "angles gamma (rad): exact DFT bins for equally spaced whole revolutions, else least squares.");

  bind_result<DriftCalibrationTag>(module, "DriftCalibrationResult", result_doc(centrifuge_spec()));
  module.def("calibrate_drift_coefficients", &calibrate, "runs"_a, py::kw_only(), "latitude_deg"_a = py::none(),
             "radius_m"_a = 1.0, "gravity_m_s2"_a = constants::kStandardGravity, "k1_rad"_a = py::none(),
             "k2_rad"_a = py::none(), "delta_omega_rad_s"_a = py::none(), "compensation"_a = true,
             "estimate_errors"_a = false, "rank_threshold"_a = 1e-4,
             "The ten drift coefficients D_F, D_I, D_O, D_S, D_II, D_OO, D_SS, D_IO, D_IS, D_OS of eq. (2) by least\n"
             "squares q = (Phi^T Phi)^-1 Phi^T (Y - epsilon) (centrifuge paper, eqs. 12-16), with the\n"
             "Earth rate and the centrifuge errors k1, k2, delta-omega compensated (epsilon), and the influence\n"
             "of each error (paper section 6). As the CLI's centrifuge command: latitude_deg is required\n"
             "unless compensation=False; unmeasured errors are 0 unless estimate_errors (two or more g-levels).\n"
             "gravity_m_s2 is the site's gravity (A = Omega^2 R0 / g); the coefficients are per standard g\n"
             "(9.80665 m/s^2, the g of deg/h/g), converted from it.");
  module.def("centrifuge_model_output", &model_output, "coefficients"_a, "omega_rad_s"_a, "beta_rad"_a,
             "gamma_rad"_a, py::kw_only(), "radius_m"_a = 1.0, "latitude_deg"_a = 0.0,
             "gravity_m_s2"_a = constants::kStandardGravity, "k1_rad"_a = 0.0, "k2_rad"_a = 0.0,
             "delta_omega_rad_s"_a = 0.0,
             "The first-order model's noise-free gyro output (deg/h) at every gamma: eq. (2) with the inputs of\n"
             "eqs. (5)-(8) of the centrifuge paper; coefficients in the order D_F ... D_OS, per standard g.");
  py::list names;
  for (std::size_t term = 0; term < kDriftTermCount; ++term) names.append(std::string(drift_term_name(term)));
  module.attr("DRIFT_TERMS") = py::tuple(names);
}

}  // namespace inertest::python
