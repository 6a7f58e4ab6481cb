// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/plan.hpp"

#include <cmath>

#include "quad/common/time.hpp"

namespace quad::display {

std::vector<TracePose> planPoses(const trajectory::Trajectory& t, double period)
{
  std::vector<TracePose> out;
  if (t.empty() || !(period > 0.0)) {
    return out;
  }
  double heading = 0.0;  // [rad] about world z
  const auto pose = [&](double time) {
    const trajectory::State s = t.at(time);
    if (s.v.head<2>().norm() > 1e-3) {
      heading = std::atan2(s.v.y(), s.v.x());
    }
    out.push_back({common::toNanoseconds(time), s.p, geometry::fromAxisAngle(Vector3::UnitZ(), heading)});
  };
  const auto steps = static_cast<long>(std::floor(t.duration() / period));
  for (long k = 0; k <= steps; ++k) {
    pose(t.startTime() + static_cast<double>(k) * period);
  }
  if (t.startTime() + static_cast<double>(steps) * period < t.endTime()) {
    pose(t.endTime());
  }
  return out;
}

}  // namespace quad::display
