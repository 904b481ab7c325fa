// Simulated centrifuge drift calibration (reference section 1): at each g-level and each work-face
// angle β the gyro output is counted over 1/36 of a platform revolution (encoder-triggered), for a
// number of revolutions. Test keys:
//   g_levels = [10, 20]          # A = Ω²R0/g0
//   beta_deg = [0, 90, 180, 270]
//   revolutions = 100
//   samples_per_revolution = 36
//   temperature_c
// Writes <name>/samples.csv, the raw-sample record of plan kind "centrifuge": columns accel_g,
// beta_deg, gamma_deg (IA to the centripetal direction at the centre of the counting interval,
// from the platform encoder), omega_rad_s (main-axis rate), output (deg/h: pulses / K0).
// The plan step gives the centrifuge's measured errors k1 = Δθy2t, k2 = Δθx2t and ΔΩ.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr std::size_t kTerms = 10;     // DF DI DO DS DII DOO DSS DIO DIS DOS (eq. 2)
constexpr std::size_t kHarmonics = 5;  // k0 k1c k1s k2c k2s (eq. 11)
using Row = std::array<double, kTerms>;

// The regressors of eq. (2) at one angle γ, with the nominal inputs fI, fO, fS of eqs. (6)-(8) in
// standard g (the g of the drift coefficients, as the gyro model's specific force): a the
// centripetal force and gravity the site's gravity, both in standard g.
Row regressors(double a, double gravity, double beta, double gamma) {
  const double fi = -a * std::cos(gamma) * std::cos(beta) + gravity * std::sin(beta);
  const double fo = -a * std::sin(gamma);
  const double fs = a * std::cos(gamma) * std::sin(beta) + gravity * std::cos(beta);
  return {1.0, fi, fo, fs, fi * fi, fo * fo, fs * fs, fi * fo, fi * fs, fo * fs};
}

// Harmonic amplitudes (eq. 11) of a function of γ, by exact quadrature over 72 points (exact for
// trigonometric polynomials of degree < 36).
template <class F>
auto harmonics(F f) {
  using Value = decltype(f(0.0));
  std::array<Value, kHarmonics> k{};
  const int m = 72;
  for (int i = 0; i < m; ++i) {
    const double g = 2.0 * constants::kPi * i / m;
    const Value v = f(g);
    const double weights[kHarmonics] = {1.0, 2 * std::cos(g), 2 * std::sin(g), 2 * std::cos(2 * g), 2 * std::sin(2 * g)};
    for (std::size_t h = 0; h < kHarmonics; ++h) {
      if constexpr (std::is_same_v<Value, double>) {
        k[h] += weights[h] * v / m;
      } else {
        for (std::size_t j = 0; j < kTerms; ++j) k[h][j] += weights[h] * v[j] / m;
      }
    }
  }
  return k;
}

// Inverse of a symmetric positive definite matrix by Gauss-Jordan elimination with partial pivoting.
std::array<Row, kTerms> inverse(std::array<Row, kTerms> a) {
  std::array<Row, kTerms> inv{};
  for (std::size_t i = 0; i < kTerms; ++i) inv[i][i] = 1.0;
  for (std::size_t c = 0; c < kTerms; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < kTerms; ++r) {
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    }
    if (a[pivot][c] == 0.0) throw Error("centrifuge simulation: the g-levels and angles cannot identify all ten coefficients");
    std::swap(a[c], a[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double d = a[c][c];
    for (std::size_t j = 0; j < kTerms; ++j) {
      a[c][j] /= d;
      inv[c][j] /= d;
    }
    for (std::size_t r = 0; r < kTerms; ++r) {
      if (r == c || a[r][c] == 0.0) continue;
      const double f = a[r][c];
      for (std::size_t j = 0; j < kTerms; ++j) {
        a[r][j] -= f * a[c][j];
        inv[r][j] -= f * inv[c][j];
      }
    }
  }
  return inv;
}

}  // namespace

void generate_centrifuge(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> levels = test.optional_numbers("g_levels").value_or(std::vector<double>{10.0, 20.0});
  const std::vector<double> betas = test.optional_numbers("beta_deg").value_or(std::vector<double>{0, 90, 180, 270});
  const double revolutions = test.number_or("revolutions", 100.0);
  const double per_revolution = test.number_or("samples_per_revolution", 36.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (!(revolutions >= 1.0) || !(per_revolution >= 8.0)) {
    test.fail("revolutions must be >= 1 and samples_per_revolution >= 8");
  }
  for (const double a : levels) {
    if (!(a > 0.0)) test.fail_at("g_levels", "must be positive");
  }
  if (lab.dry_run) return;
  const GyroParameters& base = lab.gyro;
  std::string text = fmt::format("# centrifuge test '{}': {} samples per revolution, {} revolutions per run, {} degC\n"
                                 "accel_g,beta_deg,gamma_deg,omega_rad_s,output\n",
                                 name, per_revolution, revolutions, temperature);
  // Normal matrix of the coefficient fit and the shift from the IA misalignment's Earth-rate leak.
  std::array<Row, kTerms> normal{};
  Row leak_projection{};
  const double deg_h = 3600.0 / constants::kDegree;  // rad/s → deg/h
  const double a_ia = base.input_axis_misalignment_arcsec[0] * constants::kArcsecond;
  const double b_ia = base.input_axis_misalignment_arcsec[1] * constants::kArcsecond;
  const Vector3 leak_axis = {std::cos(a_ia) * std::cos(b_ia) - 1.0, std::sin(a_ia) * std::cos(b_ia), std::sin(b_ia)};
  const double df = base.bias_deg_h + base.bias_temperature_deg_h_per_c * (temperature - base.reference_temperature_c);
  const auto& d = base.drift;
  const Row drift_truth = {df, d.DI, d.DO, d.DS, d.DII, d.DOO, d.DSS, d.DIO, d.DIS, d.DOS};
  for (const double level : levels) {
    for (const double beta : betas) {
      Centrifuge c = lab.centrifuge;
      c.rate_rad_s = std::sqrt(level * constants::kStandardGravity / c.radius_m);
      c.beta_rad = beta * constants::kDegree;
      GyroParameters gyro = base;
      const double bin_rate = per_revolution * (c.rate_rad_s - c.errors.platform_rate_error) / (2.0 * constants::kPi);
      gyro.sample_rate_hz = bin_rate;
      GyroModel model(gyro, lab.random(fmt::format("{}/g{}_beta{}", name, level, beta)), 3600.0);
      const double start = model.time_s();
      const Rig rig = c.rig(lab.site, start, constant_temperature(temperature));
      const auto count = static_cast<std::size_t>(std::llround(revolutions * per_revolution));
      const auto pulses = model.record(rig, count, 8);
      for (std::size_t i = 0; i < pulses.size(); ++i) {
        const double local = (static_cast<double>(i) + 0.5) / bin_rate;
        const double gamma = std::fmod(c.gamma(local) / constants::kDegree, 360.0);
        const double output = static_cast<double>(pulses[i]) * bin_rate / base.scale_factor * 3600.0;
        fmt::format_to(std::back_inserter(text), "{},{},{:.6f},{},{}\n", exact(level), exact(beta), gamma,
                       exact(c.rate_rad_s), exact(output));
      }
      // Tolerance model: white sample noise σ_s over one counting interval; over n samples the
      // amplitude k0 has σ_s/√n and the others σ_s·√(2/n).
      const double n = static_cast<double>(count);
      const double sigma_sample = noise_of_mean_deg_s(base, 1.0 / bin_rate) * 3600.0;
      const double sigma[kHarmonics] = {sigma_sample / std::sqrt(n), sigma_sample * std::sqrt(2.0 / n),
                                        sigma_sample * std::sqrt(2.0 / n), sigma_sample * std::sqrt(2.0 / n),
                                        sigma_sample * std::sqrt(2.0 / n)};
      const double gravity = lab.site.gravity_m_s2 / constants::kStandardGravity;
      const auto phi = harmonics([&](double g) { return regressors(level, gravity, c.beta_rad, g); });
      // Known systematics the method does not model, pushed through the same fit: the Earth rate
      // leaking through the IA misalignment, and the gyro's dynamics (delay d, first-order f_c)
      // acting on the once- and twice-per-revolution output (the rate the Earth and the centrifuge
      // errors put on IA, and the drift of eq. 2 itself): the harmonic n lags by n·Ω·d + atan(nΩ/(2π f_c))
      // with gain 1/√(1 + (nΩ/(2π f_c))²); and the counter, whose count over 1/M revolution, stamped
      // at the interval's centre, has the gain sin(nπ/M)/(nπ/M) and no phase.
      const double platform = c.rate_rad_s - c.errors.platform_rate_error;
      auto ia_rate = [&](double g) {
        const double t = (g - c.gamma0_rad) / platform;
        return c.stimulus(lab.site, t, 0.0, temperature).rate;
      };
      const auto misaligned = harmonics([&](double g) { return dot(leak_axis, ia_rate(g)) * deg_h; });
      const auto rate = harmonics([&](double g) { return ia_rate(g)[0] * deg_h; });
      std::array<double, kHarmonics> leak = misaligned;
      for (int order = 1; order <= 2; ++order) {
        const double w = order * platform;
        const double counter = std::sin(order * constants::kPi / per_revolution) / (order * constants::kPi / per_revolution);
        const double corner = base.bandwidth_hz > 0.0 ? 2.0 * constants::kPi * base.bandwidth_hz : 0.0;
        const double lag = w * base.delay_ms * 1e-3 + (corner > 0.0 ? std::atan(w / corner) : 0.0);
        const double gain = counter * (corner > 0.0 ? 1.0 / std::sqrt(1.0 + (w / corner) * (w / corner)) : 1.0);
        double kc = rate[2 * order - 1];
        double ks = rate[2 * order];
        for (std::size_t j = 0; j < kTerms; ++j) {
          kc += phi[2 * order - 1][j] * drift_truth[j];
          ks += phi[2 * order][j] * drift_truth[j];
        }
        leak[2 * order - 1] += gain * (kc * std::cos(lag) - ks * std::sin(lag)) - kc;
        leak[2 * order] += gain * (kc * std::sin(lag) + ks * std::cos(lag)) - ks;
      }
      for (std::size_t h = 0; h < kHarmonics; ++h) {
        const double w = 1.0 / (sigma[h] * sigma[h]);
        for (std::size_t i = 0; i < kTerms; ++i) {
          leak_projection[i] += phi[h][i] * w * leak[h];
          for (std::size_t j = 0; j < kTerms; ++j) normal[i][j] += phi[h][i] * w * phi[h][j];
        }
      }
    }
  }
  lab.write(name + "/samples.csv", text);
  const auto covariance = inverse(normal);

  const std::array<std::pair<const char*, double>, kTerms> truth = {{{"DF", df}, {"DI", d.DI}, {"DO", d.DO},
                                                                     {"DS", d.DS}, {"DII", d.DII}, {"DOO", d.DOO},
                                                                     {"DSS", d.DSS}, {"DIO", d.DIO}, {"DIS", d.DIS},
                                                                     {"DOS", d.DOS}}};
  const char* figure_names[kTerms] = {"D_F", "D_I", "D_O", "D_S", "D_II", "D_OO", "D_SS", "D_IO", "D_IS", "D_OS"};
  for (std::size_t j = 0; j < kTerms; ++j) {
    double shift = 0.0;
    for (std::size_t i = 0; i < kTerms; ++i) shift += covariance[j][i] * leak_projection[i];
    // Per standard g (Unit::parse's g), as the gyro model's specific force and the procedure's result.
    const std::string unit = j == 0 ? "deg/h" : (j < 4 ? "deg/h/g" : "deg/h/g^2");
    lab.truth.push_back({name, std::string("drift coefficient ") + truth[j].first,
                         std::string("/coefficients/") + figure_names[j], truth[j].second, unit,
                         4.0 * std::sqrt(covariance[j][j]),
                         "4 sigma of the weighted harmonic least squares; expected includes the shift from the IA "
                         "misalignment's Earth-rate leak and the gyro's delay and bandwidth",
                         shift});
  }
  lab.plan_steps += fmt::format(
      "[[procedure]]\nkind = \"centrifuge\"\nname = \"{}\"\nfile = \"{}/samples.csv\"\nradius_m = {}\n"
      "k1_rad = {}\nk2_rad = {}\ndelta_omega_rad_s = {}\n\n",
      name, name, exact(lab.centrifuge.radius_m), exact(lab.centrifuge.errors.y2t), exact(lab.centrifuge.errors.x2t),
      exact(lab.centrifuge.errors.platform_rate_error));
  lab.tests.push_back({{"name", name}, {"kind", "centrifuge"}, {"file", name + "/samples.csv"},
                       {"g_levels", levels}, {"beta_deg", betas}, {"revolutions", revolutions},
                       {"samples_per_revolution", per_revolution}, {"temperature_c", temperature}});
}

}  // namespace inertest::sim
