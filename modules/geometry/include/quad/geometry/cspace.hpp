// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Configuration spaces. A rigid body in Rⁿ has C = Rⁿ × SO(n), of dimension
/// n + n(n−1)/2 = n(n+1)/2: 3 for a planar body (a car: x, y, θ), 6 for a body in space
/// (the quadcopter: position and attitude).

#include <cstddef>

#include "quad/geometry/quaternion.hpp"

namespace quad::geometry {

/// dim(Rⁿ × SO(n)) = n(n+1)/2. Throws std::invalid_argument for n < 1.
std::size_t cspaceDimension(int n);

/// A car's configuration in R² × S¹. θ lives on the circle: it is kept in [0, 2π), and
/// θ = 0 and θ → 2π are neighbours, not opposite ends of an interval.
class CarConfiguration {
public:
  CarConfiguration() = default;
  /// [m], [m], [rad] (any real θ; it is wrapped).
  CarConfiguration(double x, double y, double theta);

  double x() const { return x_; }
  double y() const { return y_; }
  double theta() const { return theta_; }

private:
  double x_ = 0.0;
  double y_ = 0.0;
  double theta_ = 0.0;
};

/// √(Δx² + Δy² + (L·Δθ)²) with Δθ the shorter way round the circle; `length` [m] converts the
/// heading difference to a distance (e.g. the car's wheelbase). A metric on R² × S¹.
double carDistance(const CarConfiguration& a, const CarConfiguration& b, double length = 1.0);

/// The quadcopter's configuration in R³ × SO(3): position p_W [m] and attitude q_WB.
struct Pose3 {
  Vector3 p = Vector3::Zero();
  Quaternion q = Quaternion::identity();

  /// X_WB ∘ X_BC = X_WC.
  Pose3 operator*(const Pose3& other) const;
  Pose3 inverse() const;
  /// A point in the body frame, expressed in the world frame.
  Vector3 transform(const Vector3& point_B) const;
};

}  // namespace quad::geometry
