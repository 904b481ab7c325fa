#include "inertest/sim/geometry.h"

#include <cmath>

namespace inertest::sim {

Matrix3 identity() { return {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}; }

Matrix3 rotation(Axis axis, double angle_rad) {
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  switch (axis) {
    case Axis::kX: return {{{1.0, 0.0, 0.0}, {0.0, c, -s}, {0.0, s, c}}};
    case Axis::kY: return {{{c, 0.0, s}, {0.0, 1.0, 0.0}, {-s, 0.0, c}}};
    case Axis::kZ: break;
  }
  return {{{c, -s, 0.0}, {s, c, 0.0}, {0.0, 0.0, 1.0}}};
}

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  }
  return r;
}

Matrix3 transpose(const Matrix3& a) {
  Matrix3 r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i][j] = a[j][i];
  }
  return r;
}

Vector3 multiply(const Matrix3& a, const Vector3& v) {
  return {a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2], a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
          a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2]};
}

Vector3 add(const Vector3& a, const Vector3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

Vector3 scale(const Vector3& v, double factor) { return {v[0] * factor, v[1] * factor, v[2] * factor}; }

Vector3 cross(const Vector3& a, const Vector3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Vector3& a, const Vector3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vector3 unit_vector(Axis axis) {
  Vector3 e{};
  e[static_cast<int>(axis)] = 1.0;
  return e;
}

ChainState evaluate_chain(const ChainLink* links, std::size_t count) {
  // Walk from the instrument back to the base: `after` is R_{i+1}···R_n when link i is visited.
  ChainState state;
  Matrix3 after = identity();
  for (std::size_t k = count; k-- > 0;) {
    const ChainLink& link = links[k];
    const Vector3 axis_in_last = multiply(transpose(after), unit_vector(link.axis));
    state.angular_velocity = add(state.angular_velocity, scale(axis_in_last, link.rate));
    after = multiply(rotation(link.axis, link.angle), after);
  }
  state.orientation = after;
  return state;
}

}  // namespace inertest::sim
