#include "inertest/sim/imu_tumble.h"

#include <cmath>
#include <numbers>

#include "inertest/sim/geometry.h"
#include "inertest/sim/random.h"

namespace inertest::sim {
namespace {

// Rodrigues' rotation about the unit `axis` by `angle`.
Matrix3 rotation(const Vector3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2];
  return {{{t * x * x + c, t * x * y - s * z, t * x * z + s * y},
           {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
           {t * x * z - s * y, t * y * z + s * x, t * z * z + c}}};
}

// The output of a triad for an input: diag(scale_factor) (I + M)^-1 input + bias + offset, solved
// by Cramer's rule.
Vector3 output_of(const ImuTriadTruth& truth, double offset, const Vector3& input) {
  Matrix3 t{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t[i][j] = (i == j ? 1.0 : 0.0) + truth.misalignment[i][j];
  }
  const auto determinant = [](const Matrix3& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = determinant(t);
  Vector3 output{};
  for (int j = 0; j < 3; ++j) {
    Matrix3 replaced = t;
    for (int i = 0; i < 3; ++i) replaced[i][j] = input[i];
    output[j] = truth.scale_factor[j] * determinant(replaced) / d + truth.bias[j] + offset;
  }
  return output;
}

}  // namespace

ImuRecord simulate_imu_tumble(const ImuTumbleOptions& options, std::uint64_t seed) {
  Random random(seed);
  ImuRecord record;
  record.source = "simulated tumble";
  Matrix3 attitude{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // body to the local level frame, z up
  const auto emit = [&](const Vector3& rate) {
    const Vector3 specific_force{attitude[2][0] * options.gravity_m_s2, attitude[2][1] * options.gravity_m_s2,
                                 attitude[2][2] * options.gravity_m_s2};
    const Vector3 a = output_of(options.accelerometer, options.offset, specific_force);
    const Vector3 w = output_of(options.gyro, options.offset, rate);
    record.time_s.push_back(static_cast<double>(record.time_s.size()) / options.sample_rate_hz);
    for (int j = 0; j < 3; ++j) {
      const double noisy_a = a[j] + options.accelerometer.noise * random.normal();
      const double noisy_w = w[j] + options.gyro.noise * random.normal();
      record.accelerometer[j].push_back(options.quantised ? std::round(noisy_a) : noisy_a);
      record.gyro[j].push_back(options.quantised ? std::round(noisy_w) : noisy_w);
    }
  };
  const auto hold = [&](double seconds) {
    for (auto i = static_cast<long>(seconds * options.sample_rate_hz); i > 0; --i) emit({0.0, 0.0, 0.0});
  };
  hold(options.first_still_s);
  for (std::size_t n = 0; n < options.orientations; ++n) {
    Vector3 axis{random.normal(), random.normal(), random.normal()};
    const double length = std::hypot(axis[0], axis[1], axis[2]);
    for (double& c : axis) c /= length;
    const double angle = (60.0 + 90.0 * random.uniform()) * std::numbers::pi / 180.0;
    const auto samples = static_cast<long>((2.0 + random.uniform()) * options.sample_rate_hz);
    const double duration = static_cast<double>(samples) / options.sample_rate_hz;
    const Matrix3 start = attitude;
    // The cycloidal profile: the angle turned by s = t / duration is angle (s - sin(2 pi s) / (2 pi)),
    // the speed angle / duration (1 - cos(2 pi s)). Speed and acceleration are zero at both ends, as
    // a rate table's are: the rate is smooth where the rotation meets the stills. (The profile
    // (1 - cos(pi s)) / 2 jumped in acceleration there; sampled on the rotation's first and last
    // instants, it cost any quadrature of the samples h^2 pi / (6 duration) of the angle, 3e-4 of
    // the gyro scale factor at 25 Hz.)
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    for (long i = 1; i <= samples; ++i) {
      const double s = static_cast<double>(i) / static_cast<double>(samples);
      const double speed = angle / duration * (1.0 - std::cos(kTwoPi * s));
      attitude = multiply(start, rotation(axis, angle * (s - std::sin(kTwoPi * s) / kTwoPi)));
      emit({axis[0] * speed, axis[1] * speed, axis[2] * speed});
    }
    hold(options.still_s);
  }
  return record;
}

}  // namespace inertest::sim
