// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/dead_reckoning.hpp"

#include <cmath>

#include "quad/geometry/quaternion.hpp"

namespace quad::control {

void DeadReckoning::anchor(const VehicleState& state, double t)
{
  state_ = state;
  anchor_t_ = t;
  t_ = t;
}

bool DeadReckoning::onImu(const InertialSample& sample, double t)
{
  const double rate = sample.angular_rate_B.norm();
  if (!sample.specific_force_B.allFinite() || !std::isfinite(rate) || !std::isfinite(t)) {
    return false;
  }
  if (!state_ || t <= t_) {
    return true;
  }
  const double dt = t - t_;
  const double angle = rate * dt;
  if (!std::isfinite(angle)) {
    return false;
  }
  VehicleState& s = *state_;
  // Velocity and position on the attitude at the start of the interval, then the attitude.
  const Vector3 a_W = geometry::rotate(s.q_WB, sample.specific_force_B) - Vector3(0.0, 0.0, gravity_);
  s.p_W += s.v_W * dt + 0.5 * a_W * dt * dt;
  s.v_W += a_W * dt;
  if (angle > 1e-12) {  // below, the turn is lost in the rounding of a unit quaternion
    s.q_WB = (s.q_WB * geometry::fromAxisAngle(sample.angular_rate_B, angle)).normalized();
  }
  s.w_B = sample.angular_rate_B;
  t_ = t;
  return true;
}

std::optional<VehicleState> DeadReckoning::estimate(double t, double max_imu_gap, double horizon) const
{
  if (!state_ || t - t_ > max_imu_gap || t - anchor_t_ > horizon || !state_->p_W.allFinite() ||
      !state_->v_W.allFinite()) {
    return std::nullopt;
  }
  return state_;
}

}  // namespace quad::control
