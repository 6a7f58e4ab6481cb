// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/trace.hpp"

#include <stdexcept>

#include "quad/geometry/distance.hpp"

namespace quad::display {

Trace::Trace(TraceParams params) : params_(params), spacing_(params.spacing), turn_(params.turn)
{
  if (!(params.spacing > 0.0) || !(params.turn > 0.0) || params.max_poses < 2) {
    throw std::invalid_argument("trace: spacing and turn must be positive, max_poses at least 2");
  }
}

bool Trace::add(const TracePose& pose)
{
  if (any_ && pose.t_ns <= newest_ns_) {
    return false;
  }
  any_ = true;
  newest_ns_ = pose.t_ns;
  if (!poses_.empty()) {
    const TracePose& last = poses_.back();
    const bool moved = (pose.p_W - last.p_W).norm() >= spacing_;
    const bool turned = geometry::geodesicAngle(pose.q_WB, last.q_WB) >= turn_;
    if (!moved && !turned) {
      return false;
    }
  }
  poses_.push_back(pose);
  if (poses_.size() > params_.max_poses) {
    thin();
  }
  return true;
}

void Trace::thin()
{
  // Keeps the even-numbered poses and the newest.
  const TracePose newest = poses_.back();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < poses_.size(); i += 2) {
    poses_[kept++] = poses_[i];
  }
  poses_.resize(kept);
  if (poses_.back().t_ns != newest.t_ns) {
    poses_.push_back(newest);
  }
  spacing_ *= 2.0;
  turn_ *= 2.0;
}

}  // namespace quad::display
