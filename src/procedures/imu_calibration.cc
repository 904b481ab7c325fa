// IMU triad calibration (issue 18); the method and the model are in procedures/imu_calibration.h
// (Tedaldi, Pretto and Menegatti, ICRA 2014).
#include "inertest/procedures/imu_calibration.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <string_view>

#include <boost/math/distributions/students_t.hpp>
#include <tuple>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/core/surface_gravity.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/mapped_file.h"
#include "inertest/io/output_record.h"
#include "inertest/io/text_table.h"
#include "inertest/io/time_stamps.h"
#include "inertest/numerics/least_squares.h"
#include "inertest/numerics/statistics.h"
#include "procedures/imu_calibration_internal.h"

namespace inertest {
namespace {

using Parameters = std::vector<double>;

SourceLocation at_file(const std::string& path) { return SourceLocation{path, 0, 0}; }

Vector3 multiply(const Matrix3& m, const Vector3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vector3& v) { return std::sqrt(dot(v, v)); }
Vector3 normalised(const Vector3& v) {
  const double n = norm(v);
  return {v[0] / n, v[1] / n, v[2] / n};
}
Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double median_of(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// A Gauss-Newton fit of `residuals` over `parameters` scaled by `scales` (the size of a step worth
// taking in each parameter, so that the design's columns are commensurate), with step halving
// when the sum of squares grows. The covariance is that of the last linearised step at the
// solution: s^2 (J^T J)^-1 with s^2 the residual variance (numerics/least_squares.h).
struct GaussNewtonFit {
  Parameters parameters;
  Matrix covariance;
  Matrix scaled_jacobian;  // at the solution, each column times its parameter's scale
  std::vector<double> residuals;
  std::size_t degrees_of_freedom = 0;
};

using ResidualFunction = std::function<std::vector<double>(const Parameters&)>;

double sum_of_squares(const std::vector<double>& r) {
  return std::inner_product(r.begin(), r.end(), r.begin(), 0.0);
}

// The Jacobian by central differences, each column scaled by its parameter's scale.
Matrix scaled_jacobian(const ResidualFunction& residuals, const Parameters& p, const Parameters& scales, std::size_t rows) {
  Matrix jacobian(rows, p.size());
  for (std::size_t j = 0; j < p.size(); ++j) {
    const double step = 1e-6 * scales[j];
    Parameters plus = p, minus = p;
    plus[j] += step;
    minus[j] -= step;
    const std::vector<double> up = residuals(plus), down = residuals(minus);
    for (std::size_t i = 0; i < rows; ++i) jacobian(i, j) = (up[i] - down[i]) / 2e-6;
  }
  return jacobian;
}

GaussNewtonFit gauss_newton(const ResidualFunction& residuals, Parameters p, const Parameters& scales,
                            const std::vector<std::string>& names) {
  LeastSquaresOptions options;
  options.parameter_names = names;
  options.rank_tolerance = 1e-9;
  std::vector<double> r = residuals(p);
  LeastSquaresResult step;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Matrix jacobian = scaled_jacobian(residuals, p, scales, r.size());
    std::vector<double> negative(r.size());
    std::transform(r.begin(), r.end(), negative.begin(), [](double v) { return -v; });
    step = solve_least_squares(jacobian, negative, options);
    double length = 1.0;
    Parameters next = p;
    std::vector<double> next_r;
    for (int halving = 0; halving < 30; ++halving, length /= 2.0) {
      for (std::size_t j = 0; j < p.size(); ++j) next[j] = p[j] + length * step.parameters[j] * scales[j];
      next_r = residuals(next);
      if (sum_of_squares(next_r) <= sum_of_squares(r)) break;
    }
    const double largest = std::abs(*std::max_element(step.parameters.begin(), step.parameters.end(),
                                                      [](double a, double b) { return std::abs(a) < std::abs(b); }));
    if (sum_of_squares(next_r) <= sum_of_squares(r)) {
      p = next;
      r = next_r;
    }
    if (largest < 1e-9 || length < 1e-8) break;
  }
  const Matrix jacobian = scaled_jacobian(residuals, p, scales, r.size());
  std::vector<double> negative(r.size());
  std::transform(r.begin(), r.end(), negative.begin(), [](double v) { return -v; });
  step = solve_least_squares(jacobian, negative, options);
  GaussNewtonFit fit{p, Matrix(p.size(), p.size()), jacobian, r, step.degrees_of_freedom};
  for (std::size_t j = 0; j < p.size(); ++j) {
    for (std::size_t k = 0; k < p.size(); ++k) fit.covariance(j, k) = step.covariance(j, k) * scales[j] * scales[k];
  }
  return fit;
}

// Warnings for pairs of parameters the orientations hardly separate (|correlation| > 0.95).
void warn_correlated(const GaussNewtonFit& fit, const std::vector<std::string>& names, const std::string& triad,
                     std::vector<std::string>& warnings) {
  for (std::size_t j = 0; j < names.size(); ++j) {
    for (std::size_t k = j + 1; k < names.size(); ++k) {
      const double variance = fit.covariance(j, j) * fit.covariance(k, k);
      if (!(variance > 0.0)) continue;
      const double correlation = fit.covariance(j, k) / std::sqrt(variance);
      if (std::abs(correlation) > 0.95) {
        warnings.push_back(fmt::format("{}: the orientations hardly separate {} from {} (correlation {:.3f}); add "
                                       "orientations that turn every axis up and down",
                                       triad, names[j], names[k], correlation));
      }
    }
  }
}

// The accelerometer's parameters: b (3), k = 1/scale_factor (3), then M[0][1], M[0][2], M[1][2].
const std::vector<std::string> kAccelerometerNames = {"bias x", "bias y", "bias z", "scale x", "scale y", "scale z",
                                                      "misalignment xy", "misalignment xz", "misalignment yz"};
// The gyro's (after its bias): k (3), then M[0][1], M[0][2], M[1][0], M[1][2], M[2][0], M[2][1].
const std::vector<std::string> kGyroNames = {"scale x", "scale y", "scale z", "misalignment xy", "misalignment xz",
                                             "misalignment yx", "misalignment yz", "misalignment zx", "misalignment zy"};
constexpr std::array<std::pair<int, int>, 3> kAccelerometerOffDiagonal = {{{0, 1}, {0, 2}, {1, 2}}};
constexpr std::array<std::pair<int, int>, 6> kGyroOffDiagonal = {{{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}}};

// T K of a triad from k (p[first..first+2]) and the off-diagonals of M that follow.
template <std::size_t N>
Matrix3 triad_matrix(const Parameters& p, std::size_t first, const std::array<std::pair<int, int>, N>& off_diagonal) {
  Matrix3 t{};
  for (int i = 0; i < 3; ++i) t[i][i] = 1.0;
  for (std::size_t n = 0; n < N; ++n) t[off_diagonal[n].first][off_diagonal[n].second] = p[first + 3 + n];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t[i][j] *= p[first + j];
  }
  return t;
}

// The calibration of a triad from the fitted k and off-diagonals (p[first..]) and their covariance.
template <std::size_t N>
void set_triad(TriadCalibration& triad, const GaussNewtonFit& fit, std::size_t first,
               const std::array<std::pair<int, int>, N>& off_diagonal) {
  for (std::size_t j = 0; j < 3; ++j) {
    const double k = fit.parameters[first + j];
    triad.scale_factor[j] = 1.0 / k;
    triad.scale_factor_uncertainty[j] = std::sqrt(fit.covariance(first + j, first + j)) / (k * k);
  }
  for (std::size_t n = 0; n < N; ++n) {
    const auto [i, j] = off_diagonal[n];
    triad.misalignment[i][j] = fit.parameters[first + 3 + n];
    triad.misalignment_uncertainty[i][j] = std::sqrt(fit.covariance(first + 3 + n, first + 3 + n));
  }
}

// An axis-aligned ellipsoid through the static means, sum_j k_j^2 (a_j - b_j)^2 = g^2, by linear
// least squares on centred and scaled coordinates: the starting point of the accelerometer's fit.
Parameters ellipsoid_start(const std::vector<Vector3>& means, double gravity, const std::string& source) {
  Vector3 centre{};
  for (const Vector3& m : means) {
    for (int j = 0; j < 3; ++j) centre[j] += m[j] / static_cast<double>(means.size());
  }
  double spread = 0.0;
  for (const Vector3& m : means) {
    for (int j = 0; j < 3; ++j) spread = std::max(spread, std::abs(m[j] - centre[j]));
  }
  if (!(spread > 0.0)) throw Error(at_file(source), "the accelerometer reads the same in every static interval");
  Matrix design(means.size(), 6);
  std::vector<double> ones(means.size(), 1.0);
  for (std::size_t i = 0; i < means.size(); ++i) {
    for (int j = 0; j < 3; ++j) {
      const double x = (means[i][j] - centre[j]) / spread;
      design(i, j) = x * x;
      design(i, 3 + j) = x;
    }
  }
  LeastSquaresOptions options;
  options.parameter_names = {"x^2", "y^2", "z^2", "x", "y", "z"};
  const LeastSquaresResult fit = solve_least_squares(design, ones, options);
  Parameters start(9, 0.0);
  double level = 1.0;
  for (int j = 0; j < 3; ++j) {
    const double a = fit.parameters[j];
    if (!(a > 0.0)) {
      throw Error(at_file(source), "the static intervals do not lie on an ellipsoid around the accelerometer's bias: "
                                   "turn every axis up and down");
    }
    const double offset = -fit.parameters[3 + j] / (2.0 * a);
    level += a * offset * offset;
    start[j] = centre[j] + spread * offset;
  }
  for (int j = 0; j < 3; ++j) start[3 + j] = gravity * std::sqrt(fit.parameters[j] / level) / spread;
  return start;
}

// The quaternion kinematics dq/dt = q (x) (0, w) / 2 (q: the body relative to the body at the start).
Quaternion derivative(const Quaternion& q, const Vector3& w) {
  return {0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]), 0.5 * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]),
          0.5 * (q[0] * w[1] + q[3] * w[0] - q[1] * w[2]), 0.5 * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0])};
}

Quaternion plus(const Quaternion& q, double h, const Quaternion& d) {
  return {q[0] + h * d[0], q[1] + h * d[1], q[2] + h * d[2], q[3] + h * d[3]};
}

// v expressed in the body frame at the end: R(q)^T v.
Vector3 rotate_back(const Quaternion& q, const Vector3& v) {
  const Vector3 u{-q[1], -q[2], -q[3]};
  const Vector3 t = cross(u, v);
  const Vector3 t2{2 * t[0], 2 * t[1], 2 * t[2]};
  const Vector3 c = cross(u, t2);
  return {v[0] + q[0] * t2[0] + c[0], v[1] + q[0] * t2[1] + c[1], v[2] + q[0] * t2[2] + c[2]};
}

}  // namespace

// The rate at the middle of the step [t_i, t_i+1] is the cubic through samples i - 1 .. i + 2 (shifted
// inward at either end of the record) at t = (t_i + t_i+1) / 2, in Lagrange's form on the time stamps
// (Abramowitz and Stegun, Handbook of Mathematical Functions, 25.2.2; on equal steps the weights
// (-1, 9, 9, -1) / 16): its error is O(h^4) where the rate is smooth, so the RK4 step errs by O(h^5)
// and the rotation by O(h^4). The rate interpolated linearly errs by (h^2 / 8) w'' at the middle: a
// rotation whose axis moves was second order (a turn about a fixed axis is the trapezoid rule either
// way). Samples are instantaneous rates (as sim/imu_tumble.h writes them). An IMU that logs the mean
// rate over each interval (or the delta angle over the step) is integrated as its rate half a step
// late, which leaves a turn from rest to rest unchanged; its smoothing, (h^2 / 24) w'', keeps the
// error of a moving axis second order. Where the angular acceleration jumps exactly at a sample (a
// rotation started abruptly on a sample) no rule on the samples does better than (h^2 / 12) times the
// jump; at a random phase of the sampling that error averages to none.
Quaternion attitude_change(const ImuRecord& record, std::size_t from, std::size_t to, const Matrix3& tk,
                           const Vector3& bias) {
  const std::size_t samples = record.time_s.size();
  const auto calibrated = [&](const Vector3& output) {
    return multiply(tk, Vector3{output[0] - bias[0], output[1] - bias[1], output[2] - bias[2]});
  };
  const auto output_at = [&](std::size_t i) { return Vector3{record.gyro[0][i], record.gyro[1][i], record.gyro[2][i]}; };
  const auto middle_output = [&](std::size_t i) {
    Vector3 output = output_at(i);
    if (samples < 4) {
      for (int j = 0; j < 3; ++j) output[j] = (output[j] + record.gyro[j][i + 1]) / 2;
      return output;
    }
    const std::size_t first = std::min(i == 0 ? 0 : i - 1, samples - 4);
    const double t = (record.time_s[i] + record.time_s[i + 1]) / 2;
    for (std::size_t a = first; a < first + 4; ++a) {
      double weight = 1.0;
      for (std::size_t b = first; b < first + 4; ++b) {
        if (b != a) weight *= (t - record.time_s[b]) / (record.time_s[a] - record.time_s[b]);
      }
      // Relative to sample i (the weights sum to 1): counts near 32768 lose no digits.
      for (int j = 0; j < 3; ++j) output[j] += weight * (record.gyro[j][a] - record.gyro[j][i]);
    }
    return output;
  };
  Quaternion q{1.0, 0.0, 0.0, 0.0};
  Vector3 w0 = calibrated(output_at(from));
  for (std::size_t i = from; i < to; ++i) {
    const double h = record.time_s[i + 1] - record.time_s[i];
    const Vector3 w1 = calibrated(output_at(i + 1));
    const Vector3 wm = calibrated(middle_output(i));
    const Quaternion k1 = derivative(q, w0);
    const Quaternion k2 = derivative(plus(q, h / 2, k1), wm);
    const Quaternion k3 = derivative(plus(q, h / 2, k2), wm);
    const Quaternion k4 = derivative(plus(q, h, k3), w1);
    for (int c = 0; c < 4; ++c) q[c] += h / 6 * (k1[c] + 2 * k2[c] + 2 * k3[c] + k4[c]);
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= n;
    w0 = w1;
  }
  return q;
}

namespace {

struct Motion {
  std::size_t from = 0;  // the last sample of a static
  std::size_t to = 0;    // the first sample of the next
  Vector3 gravity_before{};  // the unit gravity direction in the body frame, from the accelerometer
  Vector3 gravity_after{};
  Vector3 tangent_1{};  // orthonormal to gravity_after: the directions of the residual
  Vector3 tangent_2{};
};

std::vector<double> direction_residuals(const ImuRecord& record, const std::vector<Motion>& motions, const Parameters& p,
                                        const Vector3& bias) {
  const Matrix3 tk = triad_matrix(p, 0, kGyroOffDiagonal);
  std::vector<double> r;
  r.reserve(2 * motions.size());
  for (const Motion& motion : motions) {
    const Vector3 predicted =
        rotate_back(attitude_change(record, motion.from, motion.to, tk, bias), motion.gravity_before);
    r.push_back(dot(predicted, motion.tangent_1));
    r.push_back(dot(predicted, motion.tangent_2));
  }
  return r;
}

// The gyro's fit leans on two estimates that every rotation shares: the accelerometer's calibration
// (the gravity directions at either end) and the gyro's bias (integrated over each rotation). Their
// errors do not show in the scatter of the residuals, so s^2 (J^T J)^-1 alone understates the gyro's
// covariance. Each is carried in by the fit's linear sensitivity to it, dp = -(J^T J)^-1 J^T (dr/dx)
// dx, and added: C_gyro += S C_x S^T (the first-order covariance of a two-step estimate: Murphy and
// Topel, J. Bus. Econ. Stat. 3 (1985), theorem 1). dr/dx by central differences of a tenth of a sigma.
void add_shared_covariance(GaussNewtonFit& gyro, const Parameters& scales, const GaussNewtonFit& accelerometer, const TriadCalibration& gyro_triad,
                           const std::function<std::vector<double>(const Parameters&, const Vector3&)>& residuals_at) {
  const std::size_t n = gyro.parameters.size();
  const std::size_t calibration_size = accelerometer.parameters.size();
  const std::size_t shared = calibration_size + 3;
  Matrix shared_covariance(shared, shared);
  for (std::size_t j = 0; j < calibration_size; ++j) {
    for (std::size_t k = 0; k < calibration_size; ++k) shared_covariance(j, k) = accelerometer.covariance(j, k);
  }
  for (std::size_t j = 0; j < 3; ++j) {
    shared_covariance(calibration_size + j, calibration_size + j) =
        gyro_triad.bias_uncertainty[j] * gyro_triad.bias_uncertainty[j];
  }
  LeastSquaresOptions options;
  options.rank_tolerance = 1e-9;
  Matrix sensitivity(n, shared);  // d p_gyro / d x
  for (std::size_t x = 0; x < shared; ++x) {
    const double step = 0.1 * std::sqrt(shared_covariance(x, x));
    if (!(step > 0.0)) continue;
    const auto at = [&](double sign) {
      Parameters calibration = accelerometer.parameters;
      Vector3 bias = gyro_triad.bias;
      (x < calibration_size ? calibration[x] : bias[x - calibration_size]) += sign * step;
      return residuals_at(calibration, bias);
    };
    const std::vector<double> up = at(1.0), down = at(-1.0);
    std::vector<double> negative(up.size());
    for (std::size_t i = 0; i < up.size(); ++i) negative[i] = -(up[i] - down[i]) / (2.0 * step);
    const LeastSquaresResult change = solve_least_squares(gyro.scaled_jacobian, negative, options);
    for (std::size_t j = 0; j < n; ++j) sensitivity(j, x) = change.parameters[j] * scales[j];
  }
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < n; ++k) {
      double added = 0.0;
      for (std::size_t a = 0; a < shared; ++a) {
        for (std::size_t b = 0; b < shared; ++b) added += sensitivity(j, a) * shared_covariance(a, b) * sensitivity(k, b);
      }
      gyro.covariance(j, k) += added;
    }
  }
}

Vector3 interval_mean(const std::array<std::vector<double>, 3>& columns, const StaticInterval& interval) {
  Vector3 mean{};
  for (int j = 0; j < 3; ++j) {
    double sum = 0.0;
    for (std::size_t i = interval.first; i < interval.last; ++i) sum += columns[j][i] - columns[j][interval.first];
    mean[j] = columns[j][interval.first] + sum / static_cast<double>(interval.last - interval.first);
  }
  return mean;
}

// The centred moving variance over 2 half + 1 samples, summed over the three axes, from prefix sums
// of each axis less its mean; infinite where the window does not fit.
std::vector<double> moving_variance(const std::array<std::vector<double>, 3>& columns, std::size_t half) {
  const std::size_t n = columns[0].size();
  const double width = static_cast<double>(2 * half + 1);
  std::vector<double> variance(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = half; i + half < n; ++i) variance[i] = 0.0;
  for (const std::vector<double>& x : columns) {
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(n);
    std::vector<double> s1(n + 1, 0.0), s2(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      s1[i + 1] = s1[i] + (x[i] - mean);
      s2[i + 1] = s2[i] + (x[i] - mean) * (x[i] - mean);
    }
    for (std::size_t i = half; i + half < n; ++i) {
      const double sum = s1[i + half + 1] - s1[i - half];
      const double squares = s2[i + half + 1] - s2[i - half];
      variance[i] += std::max(0.0, (squares - sum * sum / width) / (width - 1.0));
    }
  }
  return variance;
}

// The variance of the rounding to the record's quantisation step q, summed over the three axes:
// q^2 / 12 each (a uniform rounding error, Widrow & Kollar, "Quantization Noise", 2008, eq. 5.3),
// q the smallest nonzero step between consecutive samples (1 for whole counts; negligible for a
// record that is not quantised).
double quantisation_variance(const std::array<std::vector<double>, 3>& columns) {
  double total = 0.0;
  for (const std::vector<double>& x : columns) {
    double step = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < x.size(); ++i) {
      const double d = std::abs(x[i] - x[i - 1]);
      if (d > 0.0) step = std::min(step, d);
    }
    if (std::isfinite(step)) total += step * step / 12.0;
  }
  return total;
}

// The median of the quietest tenth of the windows: the record's own noise; at least its rounding's
// (a quiet quantised record has windows of no variance at all, and any multiple of 0 is 0).
double quietest(const std::array<std::vector<double>, 3>& columns, const std::vector<double>& variance,
                std::size_t half) {
  std::vector<double> defined(variance.begin() + static_cast<std::ptrdiff_t>(half),
                              variance.end() - static_cast<std::ptrdiff_t>(half));
  std::sort(defined.begin(), defined.end());
  defined.resize(std::max<std::size_t>(1, defined.size() / 10));
  return std::max(median_of(defined), quantisation_variance(columns));
}

std::vector<StaticInterval*> accepted_of(std::vector<StaticInterval>& intervals) {
  std::vector<StaticInterval*> accepted;
  for (StaticInterval& interval : intervals) {
    if (interval.accepted) accepted.push_back(&interval);
  }
  return accepted;
}

// Gaps in the time stamps, as `inspect` reports them (io/time_stamps.h: a step of more than 1.5 sample
// intervals, or of coarse stamps more than a quantum over one). Inside a rotation the gyro's fit integrates (RK4 across
// the step, with the rate interpolated over it), the turn made while samples were missing is lost and the rotation's
// residual with it: an Error at the line after the gap. Elsewhere (in a static interval, or in a motion between statics
// that no fit uses) it changes nothing the fits use: a warning.
void check_time_gaps(const ImuRecord& record, const std::vector<Motion>& motions, std::vector<std::string>& warnings) {
  const TimeGaps found = find_time_gaps(record.time_s, record.lines, {});
  for (const TimeGap& time_gap : found.gaps) {
    const std::size_t k = time_gap.row - 1;  // the gap lies between samples k and k + 1
    const std::string where =
        record.lines.empty() ? fmt::format("after sample {}", k + 1) : fmt::format("before line {}", time_gap.line);
    const std::string gap = fmt::format("a gap in the time stamps: {:.6g} s to {:.6g} s, {} sample(s) of {:.6g} s missing",
                                        time_gap.time_before, time_gap.time_after, time_gap.missing,
                                        found.sample_interval);
    const auto inside = std::find_if(motions.begin(), motions.end(),
                                     [k](const Motion& motion) { return motion.from <= k && k < motion.to; });
    if (inside == motions.end()) {
      warnings.push_back(fmt::format("{} {}, outside the rotations the gyro's fit integrates", gap, where));
      continue;
    }
    const SourceLocation location =
        record.lines.empty() ? at_file(record.source) : SourceLocation{record.source, time_gap.line, 0};
    throw Error(location, fmt::format("{}{}, inside the rotation from the static interval ending at {:.6g} s to the one "
                                      "starting at {:.6g} s: the gyro's integration would lose the turn made in it",
                                      gap, record.lines.empty() ? " " + where : "", record.time_s[inside->from],
                                      record.time_s[inside->to]));
  }
}

}  // namespace

void ImuCalibrationOptions::validate() const {
  // The output units are any the unit parser knows (counts, volts, m/s^2, ...): an unknown one is its error.
  if (!accelerometer_unit.empty()) check_parameter("accelerometer_unit", [&] { Unit::parse(accelerometer_unit); });
  if (!gyro_unit.empty()) check_parameter("gyro_unit", [&] { Unit::parse(gyro_unit); });
  check_surface_gravity("gravity_m_s2", gravity_m_s2);
  if (!(static_window_s > 0.0)) throw ParameterError("static_window_s", "the moving-variance window must be positive");
  if (!(static_threshold > 1.0)) {
    throw ParameterError("static_threshold", "the threshold is a multiple of the quietest variance: more than 1");
  }
  if (!(static_minimum_s >= static_window_s)) {
    throw ParameterError("static_minimum_s", "a static interval must last at least one moving-variance window");
  }
  if (!(outlier_false_alarm > 0.0 && outlier_false_alarm < 0.5)) {
    throw ParameterError("outlier_false_alarm", "a probability between 0 and 0.5");
  }
  if (minimum_statics < 9) {
    throw ParameterError("minimum_statics", "each triad has nine parameters: at least 9 static intervals");
  }
}

Vector3 TriadCalibration::apply(const Vector3& output) const {
  Matrix3 t{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t[i][j] = ((i == j ? 1.0 : 0.0) + misalignment[i][j]) / scale_factor[j];
  }
  return multiply(t, Vector3{output[0] - bias[0], output[1] - bias[1], output[2] - bias[2]});
}

nlohmann::json triad_json(const TriadCalibration& triad) {
  nlohmann::json json = {
      {"bias", {{"value", triad.bias}, {"unit", triad.output_unit}, {"uncertainty", triad.bias_uncertainty}}},
      {"scale_factor",
       {{"value", triad.scale_factor},
        {"unit", fmt::format("{}/({})", triad.output_unit, triad.input_unit)},
        {"uncertainty", triad.scale_factor_uncertainty}}},
      {"misalignment",
       {{"value", triad.misalignment}, {"unit", "rad"}, {"uncertainty", triad.misalignment_uncertainty}}}};
  // An exact fit's zeros are no uncertainty: a certificate stated ±0 at the fewest orientations.
  if (!triad.uncertainty_known) {
    for (auto& [key, figure] : json.items()) figure.erase("uncertainty");
  }
  return json;
}

nlohmann::json calibration_file_json(const ImuCalibrationResult& result) {
  return {{"procedure", "imu_calibration"},
          {"model",
           "input = (I + misalignment) diag(1 / scale_factor) (output - bias); accelerometer input in m/s^2, "
           "gyro input in rad/s"},
          {"gravity", Figure{result.gravity_m_s2, "m/s^2", std::nullopt}},
          {"accelerometer", triad_json(result.accelerometer)},
          {"gyro", triad_json(result.gyro)}};
}

ImuCalibrationFile read_imu_calibration(const std::string& path) {
  const MappedFile file(path);
  ImuCalibrationFile read;
  try {
    const nlohmann::json json = nlohmann::json::parse(file.bytes());
    if (json.contains("gravity")) {
      const nlohmann::json& gravity = json.at("gravity");
      const std::string unit = gravity.at("unit").get<std::string>();
      try {
        read.gravity_m_s2 = convert(gravity.at("value").get<double>(), Unit::parse(unit), Unit::parse("m/s^2"));
        check_surface_gravity("gravity", *read.gravity_m_s2);
      } catch (const Error& e) {
        throw Error(at_file(path), fmt::format("gravity: {} {}: {}", gravity.at("value").dump(), unit, e.message()));
      }
    }
    for (std::size_t t = 0; t < 2; ++t) {
      const nlohmann::json& triad = json.at(t == 0 ? "accelerometer" : "gyro");
      TriadCalibration& calibration = read.triads[t];
      calibration.input_unit = t == 0 ? "m/s^2" : "rad/s";
      calibration.output_unit = triad.at("bias").at("unit").get<std::string>();
      calibration.bias = triad.at("bias").at("value").get<Vector3>();
      calibration.scale_factor = triad.at("scale_factor").at("value").get<Vector3>();
      calibration.misalignment = triad.at("misalignment").at("value").get<Matrix3>();
      calibration.uncertainty_known = triad.at("bias").contains("uncertainty");
      if (calibration.uncertainty_known) {
        calibration.bias_uncertainty = triad.at("bias").at("uncertainty").get<Vector3>();
        calibration.scale_factor_uncertainty = triad.at("scale_factor").at("uncertainty").get<Vector3>();
        calibration.misalignment_uncertainty = triad.at("misalignment").at("uncertainty").get<Matrix3>();
      }
      // The scale factor and the misalignment in the units the file states, converted to those the model
      // applies (output unit per m/s^2 or rad/s; rad), as temperature-apply converts its coefficients.
      const std::string triad_name = t == 0 ? "accelerometer" : "gyro";
      const auto factor_to = [&](const char* key, const std::string& unit) {
        const nlohmann::json& stated = triad.at(key).at("unit");
        if (!stated.is_string() || stated.get<std::string>().empty()) {
          throw Error(at_file(path), fmt::format("{}.{}: no unit (the model takes {})", triad_name, key, unit));
        }
        try {
          return convert(1.0, Unit::parse(stated.get<std::string>()), Unit::parse(unit));
        } catch (const Error& e) {
          throw Error(at_file(path), fmt::format("{}.{}: the unit '{}' does not convert to {}: {}", triad_name, key,
                                                 stated.get<std::string>(), unit, e.message()));
        }
      };
      const double scale_factor_factor =
          factor_to("scale_factor", fmt::format("{}/({})", calibration.output_unit, calibration.input_unit));
      for (int j = 0; j < 3; ++j) {
        calibration.scale_factor[j] *= scale_factor_factor;
        calibration.scale_factor_uncertainty[j] *= std::abs(scale_factor_factor);
      }
      const double misalignment_factor = factor_to("misalignment", "rad");
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          calibration.misalignment[i][j] *= misalignment_factor;
          calibration.misalignment_uncertainty[i][j] *= std::abs(misalignment_factor);
        }
      }
      for (double scale : calibration.scale_factor) {
        if (!(std::abs(scale) > 0.0)) throw Error(at_file(path), "a scale factor of 0 cannot be applied");
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(at_file(path), fmt::format("not an IMU calibration (inertest imu-calibration --export): {}", e.what()));
  }
  return read;
}

std::string imu_output_unit(const ImuRecord& record, std::size_t triad, const std::string& given) {
  const std::string& stored = record.stored_units.at(triad);
  if (stored.empty()) return given.empty() ? kUnstatedOutputUnit : given;
  if (!given.empty() && !same_unit(given, stored)) {
    throw Error(at_file(record.source), fmt::format("the {} unit given, {}, contradicts the unit {} the record stores "
                                                    "for its channels",
                                                    triad == 0 ? "accelerometer" : "gyro", given, stored));
  }
  return stored;
}

std::string imu_pulse_counts_as_rates(ImuRecord& record, std::size_t triad, const std::string& given) {
  const std::string unit = imu_output_unit(record, triad, given);
  if (!counts_pulses(unit)) return unit;
  const double rate = with_file_context(record.source, [&] { return mean_sample_rate_hz(record.time_s); });
  for (std::vector<double>& axis : triad == 0 ? record.accelerometer : record.gyro) pulse_counts_as_rates(axis, rate);
  return record.stored_units.at(triad) = output_unit_as_rate(unit);
}

ImuRecord read_imu_record(const std::string& path, const std::string& columns) {
  TextTableOptions options;
  std::string_view rest = columns;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    options.columns.push_back(ColumnSelector::parse(rest.substr(0, comma)));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
  }
  if (options.columns.size() != 7) {
    throw ParameterError("columns", fmt::format("{} columns named; an IMU record needs seven: time, ax, ay, az, gx, gy, "
                                                "gz (e.g. time_s,ax,ay,az,gx,gy,gz)",
                                                options.columns.size()));
  }
  if (const auto format = detect_channel_record_format(path)) {
    const std::unique_ptr<ChannelRecord> channels = open_channel_record(path, *format);
    std::array<std::vector<double>, 7> samples;
    for (std::size_t c = 0; c < 7; ++c) samples[c] = read_channel(*channels, channels->find(options.columns[c]));
    const ChannelInfo& time = channels->channels()[channels->find(options.columns[0])];
    const double seconds = with_file_context(path, [&] { return seconds_per_time_stamp(time.name, time.unit); });
    for (double& stamp : samples[0]) stamp *= seconds;
    for (std::size_t i = 1; i < samples[0].size(); ++i) {
      if (!(samples[0][i] > samples[0][i - 1])) {
        throw Error(at_file(path), fmt::format("the time does not increase at sample {}", i + 1));
      }
    }
    // The unit each triad's channels store, as inertest knows units (one a channel does not state, or
    // states in words inertest does not know, NI-DAQmx's "Volts", is none): one for the three, or an
    // error naming them.
    std::array<std::string, 2> stored_units;
    for (std::size_t triad = 0; triad < 2; ++triad) {
      std::vector<std::string> units;
      for (std::size_t c = 1 + 3 * triad; c < 4 + 3 * triad; ++c) {
        const ChannelInfo& info = channels->channels()[channels->find(options.columns[c])];
        try {
          Unit::parse(info.unit);
          units.push_back(info.unit);
        } catch (const Error&) {
          units.push_back("");
        }
      }
      for (const std::string& unit : units) {
        if (unit.empty()) continue;
        if (!stored_units[triad].empty() && !same_unit(unit, stored_units[triad])) {
          throw Error(at_file(path), fmt::format("the {} channels store different units ({}): one triad, one output unit",
                                                 triad == 0 ? "accelerometer" : "gyro", fmt::join(units, ", ")));
        }
        if (stored_units[triad].empty()) stored_units[triad] = unit;
      }
    }
    return {path,
            {},
            std::move(samples[0]),
            {std::move(samples[1]), std::move(samples[2]), std::move(samples[3])},
            {std::move(samples[4]), std::move(samples[5]), std::move(samples[6])},
            stored_units};
  }
  options.minimum_rows = 2;
  TextTable table = read_text_table(path, options);
  ImuRecord record;
  record.source = path;
  record.time_s = take_time_column_s(table, 0);
  record.lines = std::move(table.row_lines);
  for (int j = 0; j < 3; ++j) {
    record.accelerometer[j] = std::move(table.columns[1 + j]);
    record.gyro[j] = std::move(table.columns[4 + j]);
  }
  return record;
}

StaticDetection detect_static_intervals(const ImuRecord& record, const ImuCalibrationOptions& options) {
  const std::size_t n = record.time_s.size();
  std::vector<double> steps(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) steps[i] = record.time_s[i + 1] - record.time_s[i];
  const double step = median_of(steps);
  const std::size_t half = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.static_window_s / step / 2)));
  const std::size_t width = 2 * half + 1;
  if (n < 2 * width) {
    throw Error(at_file(record.source), fmt::format("{} samples: too short for a {} s moving-variance window of {} samples",
                                                    n, options.static_window_s, width));
  }
  StaticDetection detection;
  const std::vector<double> accelerometer = moving_variance(record.accelerometer, half);
  const std::vector<double> gyro = moving_variance(record.gyro, half);
  detection.accelerometer_noise_variance = quietest(record.accelerometer, accelerometer, half);
  detection.gyro_noise_variance = quietest(record.gyro, gyro, half);
  const auto still = [&](std::size_t i) {
    return accelerometer[i] <= options.static_threshold * detection.accelerometer_noise_variance &&
           gyro[i] <= options.static_threshold * detection.gyro_noise_variance;
  };
  for (std::size_t i = half; i + half < n;) {
    if (!still(i)) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end + half < n && still(end)) ++end;
    // The samples whose whole window is still: a window's edge may graze the motion's slow start.
    StaticInterval interval;
    interval.first = i;
    interval.last = end;
    interval.start_s = record.time_s[interval.first];
    interval.end_s = record.time_s[interval.last - 1];
    const double duration = interval.end_s - interval.start_s;
    interval.accepted = duration >= options.static_minimum_s;
    if (!interval.accepted) {
      interval.reason = fmt::format("still for {:.3g} s, shorter than the minimum {} s", duration, options.static_minimum_s);
    }
    interval.accelerometer_mean = interval_mean(record.accelerometer, interval);
    interval.gyro_mean = interval_mean(record.gyro, interval);
    detection.intervals.push_back(std::move(interval));
    i = end;
  }
  return detection;
}

ImuCalibrationResult calibrate_imu(const ImuRecord& record, const ImuCalibrationOptions& options) {
  const std::array<std::string, 2> output_units = {imu_output_unit(record, 0, options.accelerometer_unit),
                                                   imu_output_unit(record, 1, options.gyro_unit)};
  ImuCalibrationResult result;
  result.gravity_m_s2 = options.gravity_m_s2;
  StaticDetection detection = detect_static_intervals(record, options);
  result.static_intervals = std::move(detection.intervals);
  result.accelerometer_noise_variance = detection.accelerometer_noise_variance;
  result.gyro_noise_variance = detection.gyro_noise_variance;
  const auto require_enough = [&](const std::vector<StaticInterval*>& accepted) {
    if (accepted.size() >= options.minimum_statics) return;
    throw Error(at_file(record.source),
                fmt::format("{} static intervals accepted of {} found (still: the moving variance of both triads "
                            "below {} times their quietest windows'): the calibration needs at least {} orientations "
                            "held still for {} s or more",
                            accepted.size(), result.static_intervals.size(), options.static_threshold,
                            options.minimum_statics, options.static_minimum_s));
  };
  const double g = options.gravity_m_s2;

  // The accelerometer: |T K (a_i - b)| = g over the static means.
  const auto gravity_residual = [g](const Vector3& mean, const Parameters& p) {
    return norm(multiply(triad_matrix(p, 3, kAccelerometerOffDiagonal), Vector3{mean[0] - p[0], mean[1] - p[1], mean[2] - p[2]})) - g;
  };
  const auto fit_accelerometer = [&](const std::vector<Vector3>& means) {
    const ResidualFunction residuals = [&](const Parameters& p) {
      std::vector<double> r(means.size());
      for (std::size_t i = 0; i < means.size(); ++i) r[i] = gravity_residual(means[i], p);
      return r;
    };
    const Parameters start = ellipsoid_start(means, g, record.source);
    const double bias_scale = 1.0 / std::max({start[3], start[4], start[5]});
    return gauss_newton(residuals, start, {bias_scale, bias_scale, bias_scale, start[3], start[4], start[5], 1.0, 1.0, 1.0},
                        kAccelerometerNames);
  };
  // Outliers (the IMU touched or moving while "still"): one bad static drags a least-squares fit
  // toward it and hides among the residuals, so each static is judged by the fit without it. The
  // static whose removal leaves the smallest sum of squares is the candidate; its externally
  // studentised residual t = r / sqrt(s^2 + j^T C j) (r its residual from the fit without it, s^2
  // and C that fit's residual variance and covariance, j the gradient of r; Student's t with that
  // fit's degrees of freedom for a good static: Cook and Weisberg, "Residuals and Influence in
  // Regression", 1982, 2.2.2) is refused when P(|t| larger) times the number of statics is below
  // outlier_false_alarm (Bonferroni); then the next, until none is.
  const auto means_of = [](const std::vector<StaticInterval*>& statics) {
    std::vector<Vector3> means;
    for (const StaticInterval* interval : statics) means.push_back(interval->accelerometer_mean);
    return means;
  };
  GaussNewtonFit accelerometer;
  while (true) {
    const std::vector<StaticInterval*> accepted = accepted_of(result.static_intervals);
    require_enough(accepted);
    const std::vector<Vector3> means = means_of(accepted);
    accelerometer = fit_accelerometer(means);
    for (std::size_t i = 0; i < accepted.size(); ++i) accepted[i]->gravity_residual_m_s2 = accelerometer.residuals[i];
    if (accepted.size() <= std::max(options.minimum_statics, kAccelerometerNames.size() + 1)) break;
    std::size_t candidate = 0;
    GaussNewtonFit without;
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < means.size(); ++i) {
      std::vector<Vector3> others = means;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(i));
      GaussNewtonFit fit = fit_accelerometer(others);
      const double squares = sum_of_squares(fit.residuals);
      if (squares < least) {
        least = squares;
        candidate = i;
        without = std::move(fit);
      }
    }
    const double residual = gravity_residual(means[candidate], without.parameters);
    const std::size_t n = without.parameters.size();
    Parameters gradient(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const double step = 1e-3 * std::sqrt(without.covariance(k, k));
      if (!(step > 0.0)) continue;
      Parameters up = without.parameters, down = without.parameters;
      up[k] += step;
      down[k] -= step;
      gradient[k] = (gravity_residual(means[candidate], up) - gravity_residual(means[candidate], down)) / (2.0 * step);
    }
    const double degrees = static_cast<double>(without.degrees_of_freedom);
    double variance = least / degrees;
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < n; ++k) variance += gradient[j] * without.covariance(j, k) * gradient[k];
    }
    const double t = std::abs(residual) / std::sqrt(variance);
    const double probability = 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(degrees), t));
    if (!(probability * static_cast<double>(means.size()) < options.outlier_false_alarm)) break;
    accepted[candidate]->accepted = false;
    accepted[candidate]->gravity_residual_m_s2 = residual;
    accepted[candidate]->reason =
        fmt::format("its gravity residual {:.3g} m/s^2 from the fit without it is {:.1f} of its sigmas ({:.3g} m/s^2; "
                    "a good static lies that far out with probability {:.2g}): the IMU moved or was touched",
                    residual, t, std::sqrt(variance), probability);
  }
  TriadCalibration& a = result.accelerometer;
  a.output_unit = output_units[0];
  a.input_unit = "m/s^2";
  for (std::size_t j = 0; j < 3; ++j) {
    a.bias[j] = accelerometer.parameters[j];
    a.bias_uncertainty[j] = std::sqrt(accelerometer.covariance(j, j));
  }
  set_triad(a, accelerometer, 3, kAccelerometerOffDiagonal);
  result.accelerometer_residual_rms_m_s2 =
      std::sqrt(sum_of_squares(accelerometer.residuals) / static_cast<double>(accelerometer.residuals.size()));
  warn_correlated(accelerometer, kAccelerometerNames, "accelerometer", result.warnings);

  // The gyro: its bias from the statics, then T K from the gravity directions across each rotation.
  const std::vector<StaticInterval*> accepted = accepted_of(result.static_intervals);
  TriadCalibration& w = result.gyro;
  w.output_unit = output_units[1];
  w.input_unit = "rad/s";
  for (std::size_t j = 0; j < 3; ++j) {
    std::vector<double> means;
    for (const StaticInterval* interval : accepted) means.push_back(interval->gyro_mean[j]);
    const double mean = std::accumulate(means.begin(), means.end(), 0.0) / static_cast<double>(means.size());
    double squares = 0.0;
    for (double m : means) squares += (m - mean) * (m - mean);
    w.bias[j] = mean;
    w.bias_uncertainty[j] = std::sqrt(squares / static_cast<double>(means.size() - 1) / static_cast<double>(means.size()));
  }
  // The rotations between consecutive statics, with the gravity directions that the accelerometer's
  // calibration (parameters as its fit's) gives at either end.
  const auto motions_of = [&](const Parameters& calibration) {
    const Matrix3 tk = triad_matrix(calibration, 3, kAccelerometerOffDiagonal);
    const auto gravity = [&](const Vector3& mean) {
      return normalised(multiply(tk, Vector3{mean[0] - calibration[0], mean[1] - calibration[1], mean[2] - calibration[2]}));
    };
    std::vector<Motion> motions;
    for (std::size_t i = 0; i + 1 < accepted.size(); ++i) {
      Motion motion;
      motion.from = accepted[i]->last - 1;
      motion.to = accepted[i + 1]->first;
      motion.gravity_before = gravity(accepted[i]->accelerometer_mean);
      motion.gravity_after = gravity(accepted[i + 1]->accelerometer_mean);
      const Vector3 other = std::abs(motion.gravity_after[0]) < 0.9 ? Vector3{1, 0, 0} : Vector3{0, 1, 0};
      motion.tangent_1 = normalised(cross(motion.gravity_after, other));
      motion.tangent_2 = cross(motion.gravity_after, motion.tangent_1);
      motions.push_back(motion);
    }
    return motions;
  };
  const std::vector<Motion> motions = motions_of(accelerometer.parameters);
  check_time_gaps(record, motions, result.warnings);
  const ResidualFunction residuals = [&](const Parameters& p) { return direction_residuals(record, motions, p, w.bias); };
  // The scales that best turn each gravity direction into the next start the fit: one magnitude,
  // searched over twelve decades of rad/s per output unit (a counting MEMS gyro near 1e-4, an
  // analog one near 70 rad/s per V), with each axis's sign, its polarity (GJB 2426A 5.7), relative to
  // the accelerometer's (which gravity's magnitude cannot tell: its scale factors are taken
  // positive). Positive scales alone turned a reversed axis, or an analog gyro, into nonsense.
  // The magnitudes 1e-8 x 1.1^n (n < 290: to 1e4): every fourth of them for each sign pattern, then
  // those around the best for its pattern.
  std::vector<double> magnitudes = {1e-8};
  while (magnitudes.back() * 1.1 < 1e4) magnitudes.push_back(magnitudes.back() * 1.1);
  const auto trial_of = [&magnitudes](int signs, int n) {
    const double k = magnitudes[static_cast<std::size_t>(n)];
    const auto sign = [signs](int axis) { return (signs >> axis & 1) != 0 ? -1.0 : 1.0; };
    return Parameters{sign(0) * k, sign(1) * k, sign(2) * k, 0, 0, 0, 0, 0, 0};
  };
  const int last_magnitude = static_cast<int>(magnitudes.size()) - 1;
  constexpr int kCoarse = 4;
  double best = std::numeric_limits<double>::infinity();
  int best_signs = 0;
  int best_n = 0;
  const auto consider = [&](int signs, int n) {
    if (const double cost = sum_of_squares(residuals(trial_of(signs, n))); cost < best) {
      best = cost;
      best_signs = signs;
      best_n = n;
    }
  };
  for (int signs = 0; signs < 8; ++signs) {
    for (int n = 0; n <= last_magnitude; n += kCoarse) consider(signs, n);
  }
  const int coarse_n = best_n;
  for (int n = std::max(0, coarse_n - kCoarse + 1); n <= std::min(last_magnitude, coarse_n + kCoarse - 1); ++n) {
    consider(best_signs, n);
  }
  const Parameters start = trial_of(best_signs, best_n);
  const double magnitude = std::abs(start[0]);
  const Parameters gyro_scales = {magnitude, magnitude, magnitude, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  GaussNewtonFit gyro = gauss_newton(residuals, start, gyro_scales, kGyroNames);
  add_shared_covariance(gyro, gyro_scales, accelerometer, w, [&](const Parameters& calibration, const Vector3& bias) {
    return direction_residuals(record, motions_of(calibration), gyro.parameters, bias);
  });
  set_triad(w, gyro, 0, kGyroOffDiagonal);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    accepted[i + 1]->direction_residual_rad = std::hypot(gyro.residuals[2 * i], gyro.residuals[2 * i + 1]);
  }
  result.gyro_residual_rms_rad = std::sqrt(sum_of_squares(gyro.residuals) / static_cast<double>(motions.size()));
  // A good record leaves well under a milliradian; degrees mean the model does not describe it.
  if (constexpr double kDescribes = 0.05; !(result.gyro_residual_rms_rad <= kDescribes)) {
    result.warnings.push_back(fmt::format(
        "the gyro's calibration leaves {:.3g} rad ({:.3g} deg) rms between the gravity directions it predicts across "
        "the rotations and the accelerometer's: it does not describe this record (a column that is not the axis named, "
        "the IMU moved during a static, or a gyro the model cannot fit)",
        result.gyro_residual_rms_rad, result.gyro_residual_rms_rad / constants::kDegree));
  }
  // Two reversed gyro axes fit the record exactly as one reversed accelerometer axis does (the
  // gyro's third one): the gravity directions are mirrored, which two sign changes of the rotation undo.
  if (std::count_if(w.scale_factor.begin(), w.scale_factor.end(), [](double k) { return k < 0.0; }) == 2) {
    const auto positive = std::find_if(w.scale_factor.begin(), w.scale_factor.end(), [](double k) { return k > 0.0; });
    result.warnings.push_back(fmt::format(
        "two of the gyro's scale factors are negative: the record is the same if instead the accelerometer's {} axis "
        "is reversed (gravity cannot tell); check the accelerometer's polarity",
        "xyz"[positive - w.scale_factor.begin()]));
  }
  warn_correlated(gyro, kGyroNames, "gyro", result.warnings);
  for (const auto& [fit, triad, name] : {std::tuple{&accelerometer, &a, "accelerometer"}, std::tuple{&gyro, &w, "gyro"}}) {
    if (fit->degrees_of_freedom == 0) {
      triad->uncertainty_known = false;
      result.warnings.push_back(fmt::format("the {} fit has as many observations as parameters: it is exact and gives "
                                            "no uncertainty (hold more orientations)",
                                            name));
    } else if (const std::optional<std::string> few = few_degrees_of_freedom_warning(
                   fmt::format("the {} fit", name), fit->degrees_of_freedom, "calibrations")) {
      result.warnings.push_back(*few + "; hold more orientations");
    }
  }
  return result;
}

}  // namespace inertest
