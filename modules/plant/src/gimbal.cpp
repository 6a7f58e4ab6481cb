// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/gimbal.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "quad/geometry/so3.hpp"

namespace quad::plant {

Gimbal::Gimbal(GimbalConfig config, double yaw_W, double pitch) : config_(config)
{
  if (!(config_.slew_rate > 0.0) || !(config_.min_pitch <= config_.max_pitch)) {
    throw std::invalid_argument("Gimbal: the slew rate must be positive and min_pitch at most max_pitch");
  }
  yaw_ = target_yaw_ = geometry::wrapToPi(std::isfinite(yaw_W) ? yaw_W : 0.0);
  pitch_ = target_pitch_ = std::clamp(std::isfinite(pitch) ? pitch : 0.0, config_.min_pitch, config_.max_pitch);
}

bool Gimbal::aim(double yaw_W, double pitch)
{
  if (!std::isfinite(yaw_W) || !std::isfinite(pitch)) {
    return false;
  }
  target_yaw_ = geometry::wrapToPi(yaw_W);
  target_pitch_ = std::clamp(pitch, config_.min_pitch, config_.max_pitch);
  return true;
}

void Gimbal::step(double dt)
{
  if (!(dt > 0.0)) {
    return;
  }
  const double most = config_.slew_rate * dt;
  yaw_ = geometry::wrapToPi(yaw_ + std::clamp(geometry::wrapToPi(target_yaw_ - yaw_), -most, most));
  pitch_ += std::clamp(target_pitch_ - pitch_, -most, most);
}

geometry::Quaternion Gimbal::orientation_W() const
{
  // Pan about world z, then tilt about the panned y axis: a rotation of −pitch about y lifts
  // the optical axis x towards z.
  return geometry::fromAxisAngle(geometry::Vector3::UnitZ(), yaw_) * geometry::fromAxisAngle(geometry::Vector3::UnitY(), -pitch_);
}

}  // namespace quad::plant
