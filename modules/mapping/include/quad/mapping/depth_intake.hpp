// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What the mapper takes of the depth frames it is sent: a frame from a sensor it accepts,
/// mounted with a unit attitude at a finite position, taken from a body pose it knows, and not
/// a stuck camera's repeat (stuck_sensor.hpp), becomes a scan in the world; any other is
/// refused, saying why.

#include <array>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "quad/geometry/cspace.hpp"
#include "quad/mapping/mapper.hpp"
#include "quad/mapping/stuck_sensor.hpp"

namespace quad::mapping {

/// A depth frame as the camera sent it.
struct DepthFrame {
  std::string frame_id;                       ///< which sensor
  std::vector<std::array<float, 3>> points_S;  ///< [m] in the sensor's frame
  Vector3 sensor_p_B = Vector3::Zero();        ///< [m] the sensor's mount on the body
  geometry::Quaternion sensor_q_BS;
  double max_range = 0.0;                      ///< [m] the sensor's
};

class DepthIntake {
public:
  /// `frames`: the sensor frames accepted.
  explicit DepthIntake(std::set<std::string> frames) : frames_(std::move(frames)) {}

  /// The frame's scan in the world, taken from `body_W` (none: `why_no_pose` says why it is
  /// not known), or why it cannot be mapped: an unknown frame, a mount that is not a unit
  /// attitude or not finite, no pose, or the frame before's points again. Each frame is
  /// remembered for the next one's stuck check, mapped or not.
  std::variant<Scan, std::string> take(const DepthFrame& frame, const std::optional<geometry::Pose3>& body_W,
                                       const std::string& why_no_pose);

private:
  std::set<std::string> frames_;
  StuckSensorCheck stuck_;
};

}  // namespace quad::mapping
