// SPDX-License-Identifier: BSD-3-Clause
#include "quad/trajectory/curve.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace quad::trajectory {

namespace {

/// A blend takes at most this share of each of its corner's two segments, so that two blends
/// on one segment leave a straight stretch between them.
constexpr double kBlendShare = 0.45;

/// Appends the straight segment a → b (without a) at the given spacing.
void line(const Vector3& a, const Vector3& b, double spacing, std::vector<Curve::Sample>& out)
{
  const double length = (b - a).norm();
  if (length < 1e-9) {
    return;
  }
  const Vector3 t = (b - a) / length;
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  for (int i = 1; i <= n; ++i) {
    out.push_back({a + (b - a) * (static_cast<double>(i) / n), t, 0.0});
  }
}

/// Appends the quadratic Bézier P0 → P2 with control point P1 (without P0).
void blend(const Vector3& P0, const Vector3& P1, const Vector3& P2, double spacing, std::vector<Curve::Sample>& out)
{
  const double approx = (P1 - P0).norm() + (P2 - P1).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(approx / spacing)));
  const Vector3 d2 = 2.0 * (P2 - 2.0 * P1 + P0);
  for (int i = 1; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    const Vector3 p = (1 - u) * (1 - u) * P0 + 2 * (1 - u) * u * P1 + u * u * P2;
    const Vector3 d1 = 2 * (1 - u) * (P1 - P0) + 2 * u * (P2 - P1);
    const double speed = d1.norm();
    if (speed > 1e-12) {
      out.push_back({p, d1 / speed, d1.cross(d2).norm() / (speed * speed * speed)});
    } else {
      out.push_back({p, (P2 - P0).normalized(), 1e6});  // a cusp (the path turns back): stop there
    }
  }
}

}  // namespace

Curve::Curve(const std::vector<Vector3>& input, double corner_deviation, double spacing)
{
  if (input.empty() || !(corner_deviation > 0.0) || !(spacing > 0.0)) {
    throw std::invalid_argument("Curve: needs a point, and a positive corner deviation and spacing");
  }
  std::vector<Vector3> points;
  for (const Vector3& w : input) {
    if (!w.allFinite()) {
      throw std::invalid_argument("Curve: a point is not finite");
    }
    if (points.empty() || (w - points.back()).norm() > 1e-3) {
      points.push_back(w);
    }
  }
  table_.push_back({points.front(), Vector3::UnitX(), 0.0});
  const std::size_t n = points.size();
  if (n >= 2) {
    table_.front().tangent = (points[1] - points[0]).normalized();
    // Each interior corner: a blend with legs d passes ½ d sin(φ/2) from the corner (φ the
    // deflection), at its middle.
    std::vector<double> d(n, 0.0);
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const Vector3 in = points[i] - points[i - 1];
      const Vector3 out = points[i + 1] - points[i];
      const double turn = std::acos(std::clamp(in.normalized().dot(out.normalized()), -1.0, 1.0));
      const double by_deviation = turn > 1e-6 ? 2.0 * corner_deviation / std::sin(0.5 * turn) : 1e9;
      d[i] = std::min({by_deviation, kBlendShare * in.norm(), kBlendShare * out.norm()});
    }
    Vector3 cursor = points[0];
    for (std::size_t i = 1; i < n; ++i) {
      const Vector3 dir = (points[i] - points[i - 1]).normalized();
      const Vector3 blend_start = points[i] - d[i] * dir;
      line(cursor, blend_start, spacing, table_);
      cursor = blend_start;
      if (i + 1 < n && d[i] > 0.0) {
        const Vector3 blend_end = points[i] + d[i] * (points[i + 1] - points[i]).normalized();
        blend(cursor, points[i], blend_end, spacing, table_);
        cursor = blend_end;
      }
    }
  }
  s_.assign(table_.size(), 0.0);
  for (std::size_t i = 1; i < table_.size(); ++i) {
    s_[i] = s_[i - 1] + (table_[i].p - table_[i - 1].p).norm();
  }
}

Curve::Sample Curve::at(double s) const
{
  if (table_.size() == 1 || s <= 0.0) {
    return table_.front();
  }
  if (s >= length()) {
    return table_.back();
  }
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - s_.begin());
  const double span = s_[i] - s_[i - 1];
  const double u = span > 0.0 ? (s - s_[i - 1]) / span : 0.0;
  const Sample& a = table_[i - 1];
  const Sample& b = table_[i];
  const Vector3 t = a.tangent + u * (b.tangent - a.tangent);
  return {a.p + u * (b.p - a.p), t.norm() > 1e-12 ? Vector3(t.normalized()) : b.tangent,
          a.curvature + u * (b.curvature - a.curvature)};
}

}  // namespace quad::trajectory
