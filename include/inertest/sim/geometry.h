// Small fixed-size vectors and rotation matrices for the simulator's rigs and frame chains.
//
// Convention: a frame chain lists the elementary rotations from the base (the ground) to the
// instrument; Rot(axis, angle) is the matrix that maps a vector's coordinates in the rotated
// (child) frame to the parent frame, as in the homogeneous transforms of reference section 1
// (Table 1 of the centrifuge paper): v_parent = Rot(axis, angle) · v_child.
#pragma once

#include <array>
#include <cstddef>

namespace inertest::sim {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<std::array<double, 3>, 3>;

enum class Axis { kX = 0, kY = 1, kZ = 2 };

Matrix3 identity();
Matrix3 rotation(Axis axis, double angle_rad);
Matrix3 multiply(const Matrix3& a, const Matrix3& b);
Matrix3 transpose(const Matrix3& a);
Vector3 multiply(const Matrix3& a, const Vector3& v);
Vector3 add(const Vector3& a, const Vector3& b);
Vector3 scale(const Vector3& v, double factor);
Vector3 cross(const Vector3& a, const Vector3& b);
double dot(const Vector3& a, const Vector3& b);
Vector3 unit_vector(Axis axis);

// One elementary rotation of a chain at one instant: its angle and the angle's time derivative.
struct ChainLink {
  Axis axis = Axis::kZ;
  double angle = 0.0;  // rad
  double rate = 0.0;   // rad/s
};

// Orientation of the last frame of a chain and its angular velocity relative to the base frame,
// expressed in the last frame: the exact kinematics ω_n = Σ_i (R_{i+1}···R_n)ᵀ e_i θ̇_i, which keeps
// the rate terms of time-varying error angles (wobble) that the first-order result drops.
struct ChainState {
  Matrix3 orientation = identity();  // R_1···R_n: last frame → base frame
  Vector3 angular_velocity{};        // rad/s, in the last frame
};

ChainState evaluate_chain(const ChainLink* links, std::size_t count);

}  // namespace inertest::sim
