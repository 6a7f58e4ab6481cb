// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_score.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "quad/geometry/distance.hpp"

namespace quad::launch {

namespace {
constexpr std::size_t kMaxWaiting = 2000;  // samples of either side waiting for the other: 8 s at 250 Hz

double headingOf(const geometry::Quaternion& q)
{
  // The body's x axis turned into the world, projected on the ground.
  const geometry::Vector3 x = geometry::rotate(q, geometry::Vector3::UnitX());
  return std::atan2(x.y(), x.x());
}

template <typename Map>
void bound(Map& m)
{
  while (m.size() > kMaxWaiting) {
    m.erase(m.begin());
  }
}
}  // namespace

void EstimateScore::onTruth(std::int64_t t_ns, const geometry::Vector3& p_W, const geometry::Quaternion& q_WB)
{
  const Pose truth{p_W, q_WB.normalized(), geometry::Vector3::Zero()};
  if (const auto e = estimates_.find(t_ns); e != estimates_.end()) {
    score(t_ns, truth, e->second);
    estimates_.erase(estimates_.begin(), std::next(e));
    return;
  }
  truths_[t_ns] = truth;
  bound(truths_);
}

void EstimateScore::onEstimate(std::int64_t t_ns, const geometry::Vector3& p_W, const geometry::Quaternion& q_WB,
                               const geometry::Vector3& p_std, bool aligned)
{
  if (!aligned || !p_W.allFinite() || !std::isfinite(q_WB.norm()) || !(p_std.array() > 0.0).all()) {
    return;
  }
  const Pose estimate{p_W, q_WB.normalized(), p_std};
  if (const auto t = truths_.find(t_ns); t != truths_.end()) {
    score(t_ns, t->second, estimate);
    truths_.erase(truths_.begin(), std::next(t));
    return;
  }
  estimates_[t_ns] = estimate;
  bound(estimates_);
}

void EstimateScore::score(std::int64_t t_ns, const Pose& truth, const Pose& estimate)
{
  const geometry::Vector3 e = estimate.p - truth.p;
  const double p = e.norm();
  const double a = geometry::geodesicAngle(truth.q, estimate.q) * 180.0 / std::numbers::pi;
  double yaw = headingOf(estimate.q) - headingOf(truth.q);
  yaw = std::remainder(yaw, 2.0 * std::numbers::pi) * 180.0 / std::numbers::pi;
  const geometry::Vector3 z = e.cwiseQuotient(estimate.std);
  ++n_;
  sum_p2_ += p * p;
  max_p_ = std::max(max_p_, p);
  sum_a2_ += a * a;
  max_a_ = std::max(max_a_, a);
  sum_yaw2_ += yaw * yaw;
  sum_nees_ += z.squaredNorm();
  within_ += (z.cwiseAbs().array() <= 3.0).all() ? 1U : 0U;
  if (t_ns >= next_point_ns_) {
    series_.push_back({static_cast<double>(t_ns) * 1e-9, p, 3.0 * estimate.std.norm(), a, yaw});
    next_point_ns_ = (t_ns / kSeriesPeriodNs + 1) * kSeriesPeriodNs;
  }
}

std::optional<EstimateErrors> EstimateScore::errors() const
{
  if (n_ == 0) {
    return std::nullopt;
  }
  const double n = static_cast<double>(n_);
  EstimateErrors out;
  out.samples = n_;
  out.position_rms_m = std::sqrt(sum_p2_ / n);
  out.position_max_m = max_p_;
  out.attitude_rms_deg = std::sqrt(sum_a2_ / n);
  out.attitude_max_deg = max_a_;
  out.yaw_rms_deg = std::sqrt(sum_yaw2_ / n);
  out.position_nees_mean = sum_nees_ / n;
  out.within_3sigma = static_cast<double>(within_) / n;
  return out;
}

std::string toCsv(const std::vector<EstimateErrorPoint>& series)
{
  std::string out = "t_s,position_m,position_3sigma_m,attitude_deg,yaw_deg\n";
  for (const auto& p : series) {
    out += fmt::format("{:.3f},{:.4f},{:.4f},{:.3f},{:.3f}\n", p.t_s, p.position_m, p.position_3sigma_m,
                       p.attitude_deg, p.yaw_deg);
  }
  return out;
}

}  // namespace quad::launch
