#include "inertest/centrifuge/centrifuge_model.h"

#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"

namespace inertest::centrifuge {
namespace {

// 1 rad/s in deg/h: rates that enter w_d in rad/s are converted to deg/h (reference section 1).
constexpr double kDegPerHourPerRadPerSecond = 3600.0 / constants::kDegree;

// Points of the exact projection: an N-point DFT reproduces harmonics 0..2 of a trigonometric
// polynomial of degree <= 2 exactly when N > 4 (no alias k +- N lands on 0..2).
constexpr std::size_t kProjectionPoints = 8;

template <typename Function>
HarmonicAmplitudes project(Function&& function) {
  HarmonicAmplitudes amplitudes{};
  for (std::size_t i = 0; i < kProjectionPoints; ++i) {
    const double gamma = 2.0 * constants::kPi * static_cast<double>(i) / kProjectionPoints;
    const double value = function(gamma);
    for (std::size_t h = 0; h < kHarmonicCount; ++h) {
      const double weight = h == kK0 ? 1.0 : 2.0;  // DFT bin -> amplitude of cos/sin
      amplitudes[h] += weight * value * harmonic_basis(h, gamma) / kProjectionPoints;
    }
  }
  return amplitudes;
}

}  // namespace

std::string_view drift_term_name(std::size_t term) {
  static constexpr std::array<std::string_view, kDriftTermCount> kNames = {
      "D_F", "D_I", "D_O", "D_S", "D_II", "D_OO", "D_SS", "D_IO", "D_IS", "D_OS"};
  return kNames.at(term);
}

std::string_view drift_term_unit(std::size_t term) {
  if (term == kF) return "deg/h";
  if (term <= kS) return "deg/h/g";
  return "deg/h/g^2";
}

std::string_view harmonic_name(std::size_t harmonic) {
  static constexpr std::array<std::string_view, kHarmonicCount> kNames = {"k0", "k1c", "k1s", "k2c", "k2s"};
  return kNames.at(harmonic);
}

double harmonic_basis(std::size_t harmonic, double gamma_rad) {
  switch (harmonic) {
    case kK0: return 1.0;
    case kK1c: return std::cos(gamma_rad);
    case kK1s: return std::sin(gamma_rad);
    case kK2c: return std::cos(2.0 * gamma_rad);
    case kK2s: return std::sin(2.0 * gamma_rad);
    default: throw Error(fmt::format("harmonic index {} out of range", harmonic));
  }
}

namespace {

constexpr double kLongestArmM = 50.0;

}  // namespace

void CentrifugeSite::validate() const {
  if (!(std::isfinite(radius_m) && radius_m > 0.0)) {
    throw Error(fmt::format("centrifuge: the radius must be positive, got {} m", radius_m));
  }
  // A precision centrifuge's arm is metres long: 1000 is a radius in mm (D_I came out -1.48 for 1.54).
  if (radius_m > kLongestArmM) {
    throw Error(fmt::format("centrifuge: a radius of {} m is longer than any centrifuge's arm ({} m): is it in mm? "
                            "the radius is in m",
                            radius_m, kLongestArmM));
  }
  if (!(std::isfinite(gravity_m_s2) && gravity_m_s2 > 0.0)) {
    throw Error(fmt::format("centrifuge: the local gravity must be positive, got {} m/s^2", gravity_m_s2));
  }
  if (!(std::isfinite(earth_rate_rad_s) && earth_rate_rad_s > 0.0)) {
    throw Error(fmt::format("centrifuge: the Earth rate must be positive, got {} rad/s", earth_rate_rad_s));
  }
  if (!(std::isfinite(latitude_rad) && std::abs(latitude_rad) <= constants::kPi / 2.0)) {
    throw Error(fmt::format("centrifuge: the latitude must lie in [-90, 90] deg, got {} deg",
                            latitude_rad / constants::kDegree));
  }
}

CentrifugeErrors CentrifugeErrors::from_angles(double perpendicularity_y_rad, double wobble_y_rad,
                                               double perpendicularity_x_rad, double wobble_x_rad,
                                               double delta_omega_rad_s) {
  // Paper, after eq. (5): k1 = dtheta_y2t + dtheta_y2(-Omega t), k2 = dtheta_x2t + dtheta_x2(-Omega t).
  return {perpendicularity_y_rad + wobble_y_rad, perpendicularity_x_rad + wobble_x_rad, delta_omega_rad_s};
}

double centripetal_specific_force(const CentrifugeSite& site, double omega_rad_s) {
  return omega_rad_s * omega_rad_s * site.radius_m / site.gravity_m_s2;  // A = Omega^2 R0 / g
}

double coriolis_specific_force(const CentrifugeSite& site, double omega_rad_s) {
  // A_k = -2 R0 Omega omega_e sin(phi) / g
  return -2.0 * site.radius_m * omega_rad_s * site.earth_rate_rad_s * std::sin(site.latitude_rad) / site.gravity_m_s2;
}

SpecificForce centrifuge_specific_force(const CentrifugeSite& site, double omega_rad_s, double beta_rad,
                                        double gamma_rad) {
  const double a = centripetal_specific_force(site, omega_rad_s);
  const double a_k = coriolis_specific_force(site, omega_rad_s);
  const double radial = a * std::cos(gamma_rad) + a_k;
  return {
      -radial * std::cos(beta_rad) + std::sin(beta_rad),  // eq. (6)
      -a * std::sin(gamma_rad),                           // eq. (7)
      radial * std::sin(beta_rad) + std::cos(beta_rad),   // eq. (8)
  };
}

double centrifuge_input_rate(const CentrifugeSite& site, const CentrifugeErrors& errors, double omega_rad_s,
                             double beta_rad, double gamma_rad) {
  // Eq. (5), reconstructed form (reference section 1), in rad/s, then converted to deg/h.
  const double tilt = errors.k1_rad * std::cos(gamma_rad) + errors.k2_rad * std::sin(gamma_rad);
  const double horizontal = -tilt * omega_rad_s + site.earth_rate_rad_s * std::cos(site.latitude_rad);
  const double vertical = site.earth_rate_rad_s * std::sin(site.latitude_rad) + errors.delta_omega_rad_s;
  return (horizontal * std::cos(beta_rad) + vertical * std::sin(beta_rad)) * kDegPerHourPerRadPerSecond;
}

SpecificForce in_standard_g(const SpecificForce& force_site_g, const CentrifugeSite& site) {
  const double ratio = site.gravity_m_s2 / constants::kStandardGravity;  // g_site in standard g
  return {force_site_g.input * ratio, force_site_g.output * ratio, force_site_g.spin * ratio};
}

DriftCoefficients drift_regressors(const SpecificForce& f) {
  // Eq. (2), in the order of q (eq. 13).
  return {1.0,
          f.input,
          f.output,
          f.spin,
          f.input * f.input,
          f.output * f.output,
          f.spin * f.spin,
          f.input * f.output,
          f.input * f.spin,
          f.output * f.spin};
}

double centrifuge_model_output(const DriftCoefficients& coefficients, const CentrifugeSite& site,
                               const CentrifugeErrors& errors, double omega_rad_s, double beta_rad,
                               double gamma_rad) {
  const DriftCoefficients regressors =
      drift_regressors(in_standard_g(centrifuge_specific_force(site, omega_rad_s, beta_rad, gamma_rad), site));
  double output = centrifuge_input_rate(site, errors, omega_rad_s, beta_rad, gamma_rad);  // w_I of eq. (2)
  for (std::size_t j = 0; j < kDriftTermCount; ++j) output += coefficients[j] * regressors[j];
  return output;
}

HarmonicModel centrifuge_harmonic_model(const CentrifugeSite& site, double omega_rad_s, double beta_rad) {
  HarmonicModel model;
  for (std::size_t j = 0; j < kDriftTermCount; ++j) {
    const HarmonicAmplitudes column = project([&](double gamma) {
      return drift_regressors(in_standard_g(centrifuge_specific_force(site, omega_rad_s, beta_rad, gamma), site))[j];
    });
    for (std::size_t h = 0; h < kHarmonicCount; ++h) model.structure[h][j] = column[h];
  }
  // Eq. (5) is linear in (omega_e, k1, k2, dOmega): project each part alone.
  const auto rate_part = [&](const CentrifugeSite& part_site, const CentrifugeErrors& errors) {
    return project([&](double gamma) { return centrifuge_input_rate(part_site, errors, omega_rad_s, beta_rad, gamma); });
  };
  CentrifugeSite still_earth = site;
  still_earth.earth_rate_rad_s = 0.0;
  model.earth_rate = rate_part(site, CentrifugeErrors{});
  model.per_k1 = rate_part(still_earth, CentrifugeErrors{1.0, 0.0, 0.0});
  model.per_k2 = rate_part(still_earth, CentrifugeErrors{0.0, 1.0, 0.0});
  model.per_delta_omega = rate_part(still_earth, CentrifugeErrors{0.0, 0.0, 1.0});
  return model;
}

}  // namespace inertest::centrifuge
