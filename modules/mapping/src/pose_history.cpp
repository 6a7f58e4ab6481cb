// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/pose_history.hpp"

#include <algorithm>

namespace quad::mapping {

bool PoseHistory::add(std::int64_t t_ns, const geometry::Pose3& pose_WB, const geometry::Vector3& v_W)
{
  if (!samples_.empty() && t_ns <= samples_.back().t_ns) {
    return false;
  }
  samples_.push_back({t_ns, pose_WB, v_W});
  while (samples_.front().t_ns < t_ns - config_.window_ns) {
    samples_.pop_front();
  }
  return true;
}

std::optional<geometry::Pose3> PoseHistory::at(std::int64_t t_ns) const
{
  if (samples_.empty() || t_ns < samples_.front().t_ns) {
    return std::nullopt;
  }
  const Sample& newest = samples_.back();
  if (t_ns >= newest.t_ns) {
    if (t_ns - newest.t_ns > config_.max_ahead_ns) {
      return std::nullopt;
    }
    const double dt = static_cast<double>(t_ns - newest.t_ns) * 1e-9;
    return geometry::Pose3{newest.pose.p + dt * newest.v_W, newest.pose.q};
  }
  // The first state after t_ns, and the one before it.
  const auto after = std::upper_bound(samples_.begin(), samples_.end(), t_ns,
                                      [](std::int64_t t, const Sample& s) { return t < s.t_ns; });
  const Sample& b = *after;
  const Sample& a = *std::prev(after);
  if (a.t_ns == t_ns) {
    return a.pose;
  }
  if (b.t_ns - a.t_ns > config_.max_gap_ns) {
    return std::nullopt;
  }
  const double u = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  return geometry::Pose3{a.pose.p + u * (b.pose.p - a.pose.p), geometry::slerp(a.pose.q, b.pose.q, u)};
}

}  // namespace quad::mapping
