// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/depth_intake.hpp"

#include <cmath>

namespace quad::mapping {

std::variant<Scan, std::string> DepthIntake::take(const DepthFrame& frame,
                                                  const std::optional<geometry::Pose3>& body_W,
                                                  const std::string& why_no_pose)
{
  std::string problem;
  if (!frames_.contains(frame.frame_id)) {
    problem = "unknown frame '" + frame.frame_id + "'";
  } else if (!std::isfinite(frame.sensor_q_BS.norm()) || std::abs(frame.sensor_q_BS.norm() - 1.0) > 1e-3) {
    problem = "sensor attitude is not a unit quaternion";
  } else if (!frame.sensor_p_B.allFinite()) {
    problem = "sensor position is not finite";
  } else if (!body_W) {
    problem = why_no_pose;
  }
  // Every frame is remembered, so that a stuck camera's next repeat is seen whatever this one was.
  if (stuck_.repeats(frame.points_S, static_cast<float>(frame.max_range)) && problem.empty()) {
    problem = "its points repeat the cloud before it's, bit for bit (a stuck camera)";
  }
  if (!problem.empty()) {
    return problem;
  }
  const geometry::Pose3 sensor = *body_W * geometry::Pose3{frame.sensor_p_B, frame.sensor_q_BS.normalized()};
  Scan scan;
  scan.origin_W = sensor.p;
  scan.max_range = frame.max_range;
  scan.points_W.reserve(frame.points_S.size());
  for (const auto& p : frame.points_S) {
    scan.points_W.push_back(sensor.transform(Vector3(p[0], p[1], p[2])));
  }
  return scan;
}

}  // namespace quad::mapping
