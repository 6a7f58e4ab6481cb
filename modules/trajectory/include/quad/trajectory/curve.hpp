// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The geometric curve a trajectory follows: a polyline with its corners rounded by quadratic
/// Bézier blends, each passing at most `corner_deviation` from its corner (so the curve stays
/// inside a corridor the planner kept free by at least that margin), tabulated by arc length
/// with its tangent and curvature.

#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::trajectory {

using geometry::Vector3;

class Curve {
public:
  struct Sample {
    Vector3 p = Vector3::Zero();
    Vector3 tangent = Vector3::UnitX();  ///< unit
    double curvature = 0.0;              ///< [1/m]
  };

  /// Consecutive points closer than a millimetre are one. A single point gives a curve of
  /// length 0 there. Throws std::invalid_argument when there is no point, a point is not
  /// finite, or the deviation or spacing is not positive.
  Curve(const std::vector<Vector3>& points, double corner_deviation, double spacing);

  double length() const { return s_.back(); }
  /// The curve at arc length s [m] (clamped to [0, length]), interpolated in the table.
  Sample at(double s) const;
  /// The table: arc lengths [m] and the samples there.
  const std::vector<double>& arcLengths() const { return s_; }
  const std::vector<Sample>& samples() const { return table_; }

private:
  std::vector<double> s_;
  std::vector<Sample> table_;
};

}  // namespace quad::trajectory
