// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/land_detector.hpp"

#include <cmath>

namespace quad::control {

bool LandDetector::update(double t, Mode mode, const VehicleState& s, double thrust_ratio)
{
  if (!judged_) {
    // The first state: standing on what the rangefinder sees beneath, or, when no reading came
    // in time (or the controller already left DISARMED), on the ground plane.
    if (first_state_t_ < 0.0) {
      first_state_t_ = t;
    }
    const bool slow = s.v_W.norm() < config_.max_vertical_speed;
    if (range_seen_) {
      judged_ = true;
      landed_ = range_ && *range_ < config_.ground_clearance && slow;
    } else if (t - first_state_t_ >= config_.range_wait || mode != Mode::kDisarmed) {
      judged_ = true;
      landed_ = s.p_W.z() < config_.ground_clearance && slow;
    }
    return landed_;
  }
  const bool still = std::abs(s.v_W.z()) < config_.max_vertical_speed && thrust_ratio < config_.max_thrust;
  return judge(t, mode, still);
}

bool LandDetector::update(double t, Mode mode, const InertialSample& imu, double thrust_ratio)
{
  if (!judged_) {
    return landed_;  // (judged first from a state: a controller that never had one has not flown)
  }
  const bool still = std::abs(imu.specific_force_B.norm() - gravity_) < config_.rest_accel_tolerance &&
                     imu.angular_rate_B.norm() < config_.rest_rate && thrust_ratio < config_.max_thrust;
  return judge(t, mode, still);
}

bool LandDetector::judge(double t, Mode mode, bool still)
{
  switch (mode) {
    case Mode::kDisarmed:
    case Mode::kIdle:
      // Rotors off or at their minimum: where it was judged last (IDLE is entered landed; a
      // controller started in the air goes from DISARMED straight to HOVER).
      still_since_ = -1.0;
      return landed_;
    case Mode::kLand:
    case Mode::kFailsafeLand:
      if (!still) {
        still_since_ = -1.0;
      } else if (still_since_ < 0.0) {
        still_since_ = t;
      }
      landed_ = landed_ || (still_since_ >= 0.0 && t - still_since_ >= config_.hold_time);
      return landed_;
    default:
      // Taking off or flying: the controller lifts it.
      still_since_ = -1.0;
      landed_ = false;
      return landed_;
  }
}

}  // namespace quad::control
