// Simulated misalignment tests:
//
// gyro_misalignment (the misalignment paper, rate table): the gyro on a vertical fixture
// face with IA along the fixture-face normal (horizontal), the fixture turned β about the table
// face normal and the gyro α about IA, in the paper's five positions (α, β) = (0, 0), (0, 180),
// (180, 180), (90, 180), (0, 90), each at +ω and −ω over whole revolutions. Test keys:
//   rates_deg_s = [20, 30, 40], revolutions = 2, temperature_c
// Writes <name>/positions.csv (alpha_deg,beta_deg,rate_dps,output: means over whole revolutions).
// Geometry (gyro frame in table-face coordinates): Rot(z, β)·Rot(y, Δθy1)·Rot(x, α); the table face
// is Rot(x, Δθx0)·Rot(y, Δθy0) on the turning table (RateTable), so the paper's Δθx0, Δθy0 are the
// table's face_arcsec, Δθy1 the [rate_table] fixture_arcsec, and the gyro's IA misalignment (a toward
// OA, b toward SA) gives Δθz2 = sin a·cos b, Δθy2 = −sin b.
//
// input_axis_misalignment (GJB 2426A-2004 5.15): IA horizontal on the table face (along face x), the
// case axis ox = OA along the table axis in position 1, oy = SA in position 2, and each turned 180°
// about IA in positions 3 and 4; ±Ω over whole revolutions. Test keys:
//   rate_deg_s = 100, revolutions = 2, temperature_c
// Writes <name>/positions.csv (position,output_positive,output_negative). Truth: δx = sin a·cos b,
// δy = sin b, α = asin(√(δx² + δy²)), the mounting error ε = the table axis's component along IA.
//
// accelerometer_misalignment (the misalignment paper, 4-position gravity test): the accelerometer on the dividing
// head, IA along its horizontal axis, turned β about it. Test keys:
//   beta_deg = [0, 90, 180, 270], runs = 3, seconds_per_position = 60
// Writes <name>/positions.csv (beta_deg,output,run). Truth: Δθy2 = −sin b, Δθz2 = sin a·cos b of the
// accelerometer's misalignment (a toward PA, b toward OA).
//
// Every truth is the physical angle; the expected estimate adds the systematic that the rig's other
// errors (wobble, tilts, Earth rate, scale-factor nonlinearity) give, predicted by applying the
// method's closed forms to the noise-free outputs of the model.
#include <cmath>
#include <fmt/format.h>

#include "inertest/core/citations.h"
#include "inertest/core/units.h"
#include "sim/generators.h"

namespace inertest::sim {
namespace {

constexpr double kArcsec = constants::kArcsecond;

Matrix3 chain(std::initializer_list<Matrix3> factors) {
  Matrix3 m = identity();
  for (const auto& f : factors) m = multiply(m, f);
  return m;
}

// Noise-free mean output (instrument unit) over whole revolutions of a rate-table rig.
double revolution_mean(const GyroModel& model, const Rig& rig, double rate_deg_s, double start) {
  const int points = 720;
  const double period = 360.0 / std::abs(rate_deg_s);
  double total = 0.0;
  for (int i = 0; i < points; ++i) {
    const double t = start + (i + 0.5) * period / points;
    total += model.static_output_deg_s(rig(t), 1e9);
  }
  return model.parameters().scale_factor * total / points;
}

std::size_t revolution_samples(campaign::PlanTable& test, double revolutions, double rate_deg_s, double fs) {
  const double samples = revolutions * 360.0 / std::abs(rate_deg_s) * fs;
  if (std::abs(samples - std::round(samples)) > 1e-6) {
    test.fail(fmt::format("{} revolutions at {} deg/s are not a whole number of samples at {} Hz", revolutions,
                          rate_deg_s, fs));
  }
  return static_cast<std::size_t>(std::llround(samples));
}

double ia_toward_oa(const GyroParameters& g) {
  return std::sin(g.input_axis_misalignment_arcsec[0] * kArcsec) * std::cos(g.input_axis_misalignment_arcsec[1] * kArcsec);
}
double ia_toward_sa(const GyroParameters& g) { return std::sin(g.input_axis_misalignment_arcsec[1] * kArcsec); }

}  // namespace

void generate_gyro_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> rates = test.optional_numbers("rates_deg_s").value_or(std::vector<double>{20, 30, 40});
  const double revolutions = test.number_or("revolutions", 2.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (!(revolutions >= 1.0) || revolutions != std::floor(revolutions)) test.fail_at("revolutions", "must be a whole number >= 1");
  for (const double r : rates) {
    if (!(r > 0.0)) test.fail_at("rates_deg_s", "must hold positive rates (each is run both ways)");
    revolution_samples(test, revolutions, r, lab.gyro.sample_rate_hz);
  }
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  const std::array<std::array<double, 2>, 5> positions = {{{0, 0}, {0, 180}, {180, 180}, {90, 180}, {0, 90}}};
  std::string text = fmt::format("# gyro misalignment separation '{}' ({}): means over {} whole revolutions, "
                                 "{} degC\nalpha_deg,beta_deg,rate_dps,output\n",
                                 name, citations::kMisalignmentPaper, revolutions, temperature);
  std::array<double, 5> expected{};
  double noise = 0.0;  // Σ_r σ²(e_r): variance of one position's (V+ − V−)/(2·kI·ω) at each rate
  for (const double rate : rates) {
    GyroModel model(gyro, lab.random(fmt::format("{}/rate{}", name, rate)), 3600.0);
    const std::size_t samples = revolution_samples(test, revolutions, rate, fs);
    std::array<double, 5> difference{};  // noise-free V+ − V−
    for (std::size_t p = 0; p < positions.size(); ++p) {
      const auto [alpha, beta] = positions[p];
      const Matrix3 m = chain({rotation(Axis::kZ, beta * constants::kDegree), rotation(Axis::kY, lab.fixture_tilt_rad),
                               rotation(Axis::kX, alpha * constants::kDegree)});
      for (const double sign : {1.0, -1.0}) {
        const Rig rig = lab.rate_table.rig(lab.site, m, sign * rate * constants::kDegree, 0.0, model.time_s(),
                                           constant_temperature(temperature));
        model.record(rig, static_cast<std::size_t>(std::llround(fs)));  // settling, not recorded
        const double start = model.time_s();
        const auto pulses = model.record(rig, samples);
        fmt::format_to(std::back_inserter(text), "{},{},{},{}\n", exact(alpha), exact(beta), exact(sign * rate),
                       exact(mean_output(pulses, fs)));
        difference[p] += sign * revolution_mean(model, rig, sign * rate, start);
      }
    }
    // The paper's closed forms (reference README §2) on the noise-free outputs, e_j = D_j/(2·kI·ω).
    std::array<double, 5> e{};
    for (std::size_t p = 0; p < 5; ++p) e[p] = difference[p] / (2.0 * gyro.scale_factor * rate);
    const std::array<double, 5> angles = {(e[1] - e[0]) / 2, (2 * e[4] - e[1] - e[0]) / 2, (-e[0] - e[2]) / 2,
                                          (e[2] - e[1]) / 2, (2 * e[3] - e[2] - e[1]) / 2};
    for (std::size_t i = 0; i < 5; ++i) expected[i] += angles[i] / static_cast<double>(rates.size());
    // e_j is a ratio of rates (deg/s over deg/s): an angle in rad.
    const double sigma_e = std::sqrt(2.0) * noise_of_record_mean_deg_s(gyro, samples / fs) / (2.0 * rate);
    noise += sigma_e * sigma_e;
  }
  lab.write(name + "/positions.csv", text);
  // The combined least squares over R rates is the mean of the per-rate closed forms; each angle's
  // variance is c·Σ_r σ²(e_r)/R², c the sum of squares of its closed form's weights on e_j.
  const double r2 = static_cast<double>(rates.size() * rates.size());
  const std::array<double, 5> weights = {0.5, 1.5, 0.5, 0.5, 1.5};
  const std::array<double, 5> truth = {lab.rate_table.face_y_rad, lab.rate_table.face_x_rad, lab.fixture_tilt_rad,
                                       -ia_toward_sa(gyro), ia_toward_oa(gyro)};
  const std::array<const char*, 5> names = {"delta_theta_y0", "delta_theta_x0", "delta_theta_y1", "delta_theta_y2",
                                            "delta_theta_z2"};
  const std::array<const char*, 5> quantities = {"table face dtheta_y0", "table face dtheta_x0", "fixture dtheta_y1",
                                                 "gyro IA dtheta_y2", "gyro IA dtheta_z2"};
  std::array<double, 5> sigma{};
  for (std::size_t i = 0; i < 5; ++i) {
    sigma[i] = std::sqrt(weights[i] * noise / r2);
    lab.truth.push_back({name, quantities[i], names[i], truth[i] / kArcsec, "arcsec", 4.0 * sigma[i] / kArcsec,
                         "4 sigma of the least squares over the rates from the noise of each whole-revolution mean",
                         (expected[i] - truth[i]) / kArcsec});
  }
  const double gamma_true = std::hypot(truth[3], truth[4]);
  const double gamma_expected = std::hypot(expected[3], expected[4]);
  const double sigma_gamma = std::hypot(expected[3] * sigma[3], expected[4] * sigma[4]) / gamma_expected;
  lab.truth.push_back({name, "gyro IA misalignment gamma", "misalignment", gamma_true / kArcsec, "arcsec",
                       4.0 * sigma_gamma / kArcsec, "4 sigma, first order from dtheta_y2 and dtheta_z2",
                       (gamma_expected - gamma_true) / kArcsec});
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"gyro_misalignment\"\nname = \"{}\"\nfile = \"{}/positions.csv\"\n\n",
                                name, name);
  lab.tests.push_back({{"name", name}, {"kind", "gyro_misalignment"}, {"file", name + "/positions.csv"},
                       {"rates_deg_s", rates}, {"revolutions", revolutions}, {"temperature_c", temperature}});
}

void generate_input_axis_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const double rate = test.number_or("rate_deg_s", 100.0);
  const double revolutions = test.number_or("revolutions", 2.0);
  const double temperature = test.number_or("temperature_c", lab.gyro.reference_temperature_c);
  if (!(rate > 0.0)) test.fail_at("rate_deg_s", "must be positive");
  if (!(revolutions >= 1.0) || revolutions != std::floor(revolutions)) test.fail_at("revolutions", "must be a whole number >= 1");
  revolution_samples(test, revolutions, rate, lab.gyro.sample_rate_hz);
  if (lab.dry_run) return;
  const GyroParameters& gyro = lab.gyro;
  const double fs = gyro.sample_rate_hz;
  // Gyro frame (IA, OA, SA) in table-face coordinates; IA along face x.
  const std::array<Matrix3, 4> mountings = {mounting({1, 0, 0}, {0, 0, 1}), mounting({1, 0, 0}, {0, 1, 0}),
                                            mounting({1, 0, 0}, {0, 0, -1}), mounting({1, 0, 0}, {0, -1, 0})};
  const std::size_t samples = revolution_samples(test, revolutions, rate, fs);
  GyroModel model(gyro, lab.random(name), 3600.0);
  std::string text = fmt::format("# input axis misalignment '{}' (GJB 2426A 5.15): means over {} whole revolutions at "
                                 "+-{} deg/s, {} degC\nposition,output_positive,output_negative\n",
                                 name, revolutions, rate, temperature);
  std::array<double, 4> delta{};  // noise-free δj of eqs. (47)-(48)
  for (std::size_t p = 0; p < 4; ++p) {
    std::array<double, 2> means{};
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1.0 : -1.0;
      const Rig rig = lab.rate_table.rig(lab.site, mountings[p], sign * rate * constants::kDegree, 0.0, model.time_s(),
                                         constant_temperature(temperature));
      model.record(rig, static_cast<std::size_t>(std::llround(fs)));
      const double start = model.time_s();
      means[s] = mean_output(model.record(rig, samples), fs);
      delta[p] += sign * revolution_mean(model, rig, sign * rate, start) / (2.0 * gyro.scale_factor * rate);
    }
    fmt::format_to(std::back_inserter(text), "{},{},{}\n", p + 1, exact(means[0]), exact(means[1]));
  }
  lab.write(name + "/positions.csv", text);
  // δx = (δ1 − δ3)/2 has σ = σ_V/(2·K·Ω) from four means of σ_V; ε = Σδ/4 the same.
  const double sigma = noise_of_record_mean_deg_s(gyro, samples / fs) / (2.0 * rate);  // rad
  const double dx = ia_toward_oa(gyro);
  const double dy = ia_toward_sa(gyro);
  const double ex = (delta[0] - delta[2]) / 2.0;
  const double ey = (delta[1] - delta[3]) / 2.0;
  // The table axis in face coordinates is (−sin Δθy0·cos Δθx0, sin Δθx0, ·): its IA component.
  const double epsilon = -std::sin(lab.rate_table.face_y_rad) * std::cos(lab.rate_table.face_x_rad);
  const double epsilon_expected = (delta[0] + delta[1] + delta[2] + delta[3]) / 4.0;
  const std::string basis = "4 sigma from the noise of the whole-revolution means";
  lab.truth.push_back({name, "IA tilt toward ox", "misalignment_toward_ox", dx / kArcsec, "arcsec",
                       4.0 * sigma / kArcsec, basis, (ex - dx) / kArcsec});
  lab.truth.push_back({name, "IA tilt toward oy", "misalignment_toward_oy", dy / kArcsec, "arcsec",
                       4.0 * sigma / kArcsec, basis, (ey - dy) / kArcsec});
  const double alpha = std::asin(std::hypot(dx, dy));
  const double alpha_expected = std::asin(std::hypot(ex, ey));
  lab.truth.push_back({name, "IA misalignment alpha", "misalignment", alpha / kArcsec, "arcsec", 4.0 * sigma / kArcsec,
                       basis, (alpha_expected - alpha) / kArcsec});
  lab.truth.push_back({name, "fixture mounting error epsilon", "mounting_error", epsilon / kArcsec, "arcsec",
                       4.0 * sigma / kArcsec, basis, (epsilon_expected - epsilon) / kArcsec});
  lab.plan_steps += fmt::format(
      "[[procedure]]\nkind = \"input_axis_misalignment\"\nname = \"{}\"\nfile = \"{}/positions.csv\"\nrate = {}\n\n", name,
      name, exact(rate));
  lab.tests.push_back({{"name", name}, {"kind", "input_axis_misalignment"}, {"file", name + "/positions.csv"},
                       {"rate_deg_s", rate}, {"revolutions", revolutions}, {"temperature_c", temperature}});
}

void generate_accelerometer_misalignment(campaign::PlanTable& test, const std::string& name, Lab& lab) {
  const std::vector<double> betas = test.optional_numbers("beta_deg").value_or(std::vector<double>{0, 90, 180, 270});
  const double runs = test.number_or("runs", 3.0);
  const double seconds = test.number_or("seconds_per_position", 60.0);
  if (!(runs >= 1.0) || runs != std::floor(runs)) test.fail_at("runs", "must be a whole number >= 1");
  if (!(seconds > 0.0)) test.fail_at("seconds_per_position", "must be positive");
  if (betas != std::vector<double>{0, 90, 180, 270}) test.fail_at("beta_deg", "the 4-position test uses 0, 90, 180, 270");
  if (lab.dry_run) return;
  const AccelerometerParameters& acc = lab.accelerometer;
  AccelerometerModel model(acc, lab.random(name));
  const std::size_t samples = lab.samples(seconds, acc.sample_rate_hz);
  std::string text = fmt::format("# accelerometer 4-position test '{}' ({}): mean output over {} s per position\n"
                                 "beta_deg,output,run\n",
                                 name, citations::kMisalignmentPaper, seconds);
  // Dividing head: axis north, tilted up by Δθy0, the fixture by Δθy1, the accelerometer turned β
  // about IA; gravity's specific force is 1 g up (site gravity in g).
  const Vector3 up = lab.site.specific_force_enu_g();
  std::array<double, 4> clean{};
  for (std::size_t b = 0; b < 4; ++b) {
    const Matrix3 m = chain({mounting({0, 1, 0}, {-1, 0, 0}), rotation(Axis::kY, lab.dividing_head_tilt_rad),
                             rotation(Axis::kY, lab.dividing_head_fixture_rad),
                             rotation(Axis::kX, betas[b] * constants::kDegree)});
    clean[b] = model.noise_free_output(multiply(transpose(m), up));
  }
  for (int run = 1; run <= static_cast<int>(runs); ++run) {
    for (std::size_t b = 0; b < 4; ++b) {
      const Matrix3 m = chain({mounting({0, 1, 0}, {-1, 0, 0}), rotation(Axis::kY, lab.dividing_head_tilt_rad),
                               rotation(Axis::kY, lab.dividing_head_fixture_rad),
                               rotation(Axis::kX, betas[b] * constants::kDegree)});
      const auto out = model.record(multiply(transpose(m), up), samples);
      double total = 0.0;
      for (const double v : out) total += v;
      fmt::format_to(std::back_inserter(text), "{},{},{}\n", exact(betas[b]), exact(total / samples), run);
    }
  }
  lab.write(name + "/positions.csv", text);
  // Closed forms (reference README §2): Δθy2 = (V(π) − V(0))/(2kI), Δθz2 = (V(π/2) − V(3π/2))/(2kI);
  // each of σ = √2·σ_V/(2kI) per run, the mean of the runs /√runs. σ_V: white noise n/√(2T) in g plus
  // the voltmeter quantum's uniform error per sample.
  const double y2 = -std::sin(acc.misalignment_arcsec[1] * kArcsec);
  const double z2 = std::sin(acc.misalignment_arcsec[0] * kArcsec) * std::cos(acc.misalignment_arcsec[1] * kArcsec);
  const double y2_expected = (clean[2] - clean[0]) / (2.0 * acc.scale_factor);
  const double z2_expected = (clean[1] - clean[3]) / (2.0 * acc.scale_factor);
  const double q = acc.output_resolution / acc.scale_factor;
  const double sigma_v = std::sqrt(std::pow(acc.noise_ug_rt_hz * 1e-6, 2) / (2.0 * seconds) + q * q / 12.0 / samples);
  const double sigma = std::sqrt(2.0) * sigma_v / 2.0 / std::sqrt(runs);
  const std::string basis = "4 sigma of the mean over the runs from the noise of each position's mean";
  lab.truth.push_back({name, "accelerometer IA dtheta_y2", "delta_theta_y2", y2 / kArcsec, "arcsec", 4.0 * sigma / kArcsec,
                       basis, (y2_expected - y2) / kArcsec});
  lab.truth.push_back({name, "accelerometer IA dtheta_z2", "delta_theta_z2", z2 / kArcsec, "arcsec", 4.0 * sigma / kArcsec,
                       basis, (z2_expected - z2) / kArcsec});
  // The plan's [instrument] is the gyro: the accelerometer's own K and output unit are the step's.
  lab.plan_steps += fmt::format("[[procedure]]\nkind = \"accelerometer_misalignment\"\nname = \"{}\"\n"
                                "file = \"{}/positions.csv\"\nscale_factor = {}\noutput_unit = \"{}\"\n\n",
                                name, name, exact(acc.scale_factor), acc.output_unit);
  lab.tests.push_back({{"name", name}, {"kind", "accelerometer_misalignment"}, {"file", name + "/positions.csv"},
                       {"accelerometer", acc.to_json()}, {"runs", runs}, {"seconds_per_position", seconds}});
}

}  // namespace inertest::sim
