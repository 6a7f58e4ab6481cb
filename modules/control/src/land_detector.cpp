// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/land_detector.hpp"

#include <cmath>

namespace quad::control {

bool LandDetector::update(double t, Mode mode, const VehicleState& s, double thrust_ratio)
{
  if (!judged_) {
    judged_ = true;
    landed_ = s.p_W.z() < config_.ground_clearance && s.v_W.norm() < config_.max_vertical_speed;
    return landed_;
  }
  switch (mode) {
    case Mode::kDisarmed:
    case Mode::kIdle:
      // Rotors off or at their minimum: where it was judged last (IDLE is entered landed; a
      // controller started in the air goes from DISARMED straight to HOVER).
      still_since_ = -1.0;
      return landed_;
    case Mode::kLand:
    case Mode::kFailsafeLand: {
      const bool still = std::abs(s.v_W.z()) < config_.max_vertical_speed && thrust_ratio < config_.max_thrust;
      if (!still) {
        still_since_ = -1.0;
      } else if (still_since_ < 0.0) {
        still_since_ = t;
      }
      landed_ = landed_ || (still_since_ >= 0.0 && t - still_since_ >= config_.hold_time);
      return landed_;
    }
    default:
      // Taking off or flying: the controller lifts it.
      still_since_ = -1.0;
      landed_ = false;
      return landed_;
  }
}

}  // namespace quad::control
