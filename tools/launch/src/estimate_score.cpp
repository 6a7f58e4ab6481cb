// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/estimate_score.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
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

void EstimateScore::onTruth(std::int64_t t_ns, const geometry::Vector3& p_W, const geometry::Quaternion& q_WB,
                            const geometry::Vector3& v_W)
{
  if (t_ns > end_ns_) {
    return;
  }
  const Pose truth{p_W, q_WB.normalized(), geometry::Vector3::Zero(), v_W.norm()};
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
  if (t_ns > end_ns_ || !aligned || !p_W.allFinite() || !std::isfinite(q_WB.norm()) ||
      !(p_std.array() > 0.0).all()) {
    return;
  }
  const Pose estimate{p_W, q_WB.normalized(), p_std, 0.0};
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
  double yaw = headingOf(estimate.q) - headingOf(truth.q);
  yaw = std::remainder(yaw, 2.0 * std::numbers::pi) * 180.0 / std::numbers::pi;
  const geometry::Vector3 z = e.cwiseQuotient(estimate.std);
  held_[t_ns] = {e.norm(), 3.0 * estimate.std.norm(),
                 geometry::geodesicAngle(truth.q, estimate.q) * 180.0 / std::numbers::pi, yaw, z.squaredNorm(),
                 (z.cwiseAbs().array() <= 3.0).all(), truth.speed};
  commitBefore(held_.rbegin()->first - kHoldNs);
}

void EstimateScore::commitBefore(std::int64_t t_ns)
{
  while (!held_.empty() && held_.begin()->first < t_ns) {
    const auto [t, term] = *held_.begin();
    held_.erase(held_.begin());
    ++n_;
    sum_p2_ += term.position_m * term.position_m;
    max_p_ = std::max(max_p_, term.position_m);
    sum_a2_ += term.attitude_deg * term.attitude_deg;
    max_a_ = std::max(max_a_, term.attitude_deg);
    sum_yaw2_ += term.yaw_deg * term.yaw_deg;
    sum_nees_ += term.nees;
    within_ += term.within_3sigma ? 1U : 0U;
    if (std::isfinite(term.speed)) {
      const auto above = std::upper_bound(kSpeedBands.begin(), kSpeedBands.end(), term.speed);
      BandSums& band = bands_[static_cast<std::size_t>(std::distance(kSpeedBands.begin(), above)) - 1];
      ++band.n;
      band.sum_p2 += term.position_m * term.position_m;
      band.sum_nees += term.nees;
    }
    if (t >= next_point_ns_) {
      series_.push_back({static_cast<double>(t) * 1e-9, term.position_m, term.position_3sigma_m, term.attitude_deg,
                         term.yaw_deg});
      next_point_ns_ = (t / kSeriesPeriodNs + 1) * kSeriesPeriodNs;
    }
  }
}

void EstimateScore::endAt(std::int64_t t_ns)
{
  end_ns_ = std::min(end_ns_, t_ns);
  held_.erase(held_.upper_bound(end_ns_), held_.end());
  truths_.erase(truths_.upper_bound(end_ns_), truths_.end());
  estimates_.erase(estimates_.upper_bound(end_ns_), estimates_.end());
}

EstimateScore EstimateScore::committed() const
{
  EstimateScore all = *this;
  all.commitBefore(std::numeric_limits<std::int64_t>::max());
  return all;
}

std::vector<EstimateErrorPoint> EstimateScore::series() const { return committed().series_; }

std::optional<EstimateErrors> EstimateScore::errors() const
{
  const EstimateScore all = committed();
  if (all.n_ == 0) {
    return std::nullopt;
  }
  const double n = static_cast<double>(all.n_);
  EstimateErrors out;
  out.samples = all.n_;
  out.position_rms_m = std::sqrt(all.sum_p2_ / n);
  out.position_max_m = all.max_p_;
  out.attitude_rms_deg = std::sqrt(all.sum_a2_ / n);
  out.attitude_max_deg = all.max_a_;
  out.yaw_rms_deg = std::sqrt(all.sum_yaw2_ / n);
  out.position_nees_mean = all.sum_nees_ / n;
  out.within_3sigma = static_cast<double>(all.within_) / n;
  for (std::size_t i = 0; i < kSpeedBands.size(); ++i) {
    const BandSums& b = all.bands_[i];
    if (b.n > 0) {
      const double bn = static_cast<double>(b.n);
      out.by_speed.push_back({kSpeedBands[i],
                              i + 1 < kSpeedBands.size() ? kSpeedBands[i + 1] : std::numeric_limits<double>::infinity(),
                              b.n, std::sqrt(b.sum_p2 / bn), b.sum_nees / bn});
    }
  }
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
