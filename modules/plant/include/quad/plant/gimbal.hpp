// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A two-axis camera gimbal stabilised in the world frame, as survey multirotors carry: pan
/// about world z, then tilt about the panned y axis, so the optical axis keeps its pointing
/// whatever the body's roll and pitch. Each axis slews towards its target at a bounded rate;
/// tilt is limited to its mechanical range. The controller points it where the path goes,
/// so a climb, a dip or a turn is seen before it is flown.

#include "quad/geometry/quaternion.hpp"

namespace quad::plant {

struct GimbalConfig {
  bool enabled = false;        ///< false: the camera is fixed to the body (DepthCameraConfig's mount)
  double slew_rate = 3.0;      ///< [rad/s] per axis
  double min_pitch = -1.5707963267948966;  ///< [rad] lowest elevation of the optical axis (straight down)
  double max_pitch = 1.5707963267948966;   ///< [rad] highest (straight up)
};

class Gimbal {
public:
  /// Starts (and aims) at `yaw_W` [rad, from world x towards y] and `pitch` [rad, elevation,
  /// positive up, clamped to the range]. Throws std::invalid_argument on a non-positive slew
  /// rate or an empty range.
  Gimbal(GimbalConfig config, double yaw_W, double pitch);

  /// Aims at a new target; refused (false, the old target kept) when not finite. The pitch is
  /// clamped to the range.
  bool aim(double yaw_W, double pitch);
  /// Slews both axes towards the target for dt [s]; yaw the short way round.
  void step(double dt);

  double yaw() const { return yaw_; }      ///< [rad] world frame, in (−π, π]
  double pitch() const { return pitch_; }  ///< [rad] elevation
  const GimbalConfig& config() const { return config_; }
  /// q_WS: rotates camera-frame vectors (x along the optical axis, y left, z up) into the world.
  geometry::Quaternion orientation_W() const;

private:
  GimbalConfig config_;
  double yaw_;
  double pitch_;
  double target_yaw_;
  double target_pitch_;
};

}  // namespace quad::plant
