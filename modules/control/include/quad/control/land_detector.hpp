// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Whether the vehicle rests on the ground, judged from what the controller knows (PX4's land
/// detector, reduced to its core): a state estimate says where the vehicle is, not whether it
/// touches the ground. In a landing it has landed once it stopped sinking while the controller
/// asks for less thrust than its weight (the ground holds it up), for a while. Taking off, it
/// leaves the ground. The first state, before any command, is judged by the downward
/// rangefinder and speed: standing on whatever is beneath it (a floor, a platform, a roof),
/// or flying (a controller started while the vehicle flies must not take it for landed).
/// Without a rangefinder reading in time, by height above the ground plane.
///
/// Without any state (a blind failsafe descent: the estimator lost) the IMU alone judges it:
/// at rest the accelerometer reads gravity and the gyroscope nothing, while a descent on less
/// than the weight reads less than gravity.

#include <optional>

#include "quad/control/dead_reckoning.hpp"
#include "quad/control/geometric_controller.hpp"
#include "quad/control/modes.hpp"

namespace quad::control {

struct LandDetectorConfig {
  double max_vertical_speed = 0.2;  ///< [m/s] sinking or climbing slower than this ...
  double max_thrust = 0.9;          ///< ... on less than this fraction of the weight ...
  double hold_time = 0.5;           ///< [s] ... for this long: landed
  /// [m] The first state: standing when the rangefinder reads less than this below the body
  /// (without a reading within range_wait: when below this height above the ground plane
  /// z = 0), and slower than max_vertical_speed in every direction.
  double ground_clearance = 0.3;
  /// [s] How long after the first state the first judgment waits for a rangefinder reading,
  /// while DISARMED; 0: it judges by height at once.
  double range_wait = 0.25;
  /// Without a state: at rest when the specific force is within this of gravity [m/s²] ...
  double rest_accel_tolerance = 0.5;
  double rest_rate = 0.2;  ///< [rad/s] ... and the body turns slower than this
};

class LandDetector {
public:
  explicit LandDetector(LandDetectorConfig config = {}, double gravity = 9.81) : config_(config), gravity_(gravity) {}

  /// A tick at time t [s] in `mode` with the state `s` and the thrust the controller last
  /// commanded, as a fraction of the weight. Returns whether the vehicle is landed.
  bool update(double t, Mode mode, const VehicleState& s, double thrust_ratio);
  /// The same without a state, from an IMU sample (specific force, angular rate).
  bool update(double t, Mode mode, const InertialSample& imu, double thrust_ratio);
  /// A downward rangefinder's reading [m below the body's origin]; none: nothing in range.
  void onRange(std::optional<double> range) { range_ = range; range_seen_ = true; }
  bool landed() const { return landed_; }
  /// The first state has been judged. Before, landed() is true (nothing takes over in the air)
  /// but the vehicle must not be armed: it may be flying.
  bool judged() const { return judged_; }

private:
  /// A tick whose landing conditions (`still`, in a landing) did or did not hold.
  bool judge(double t, Mode mode, bool still);

  LandDetectorConfig config_;
  double gravity_;  ///< [m/s²]
  bool judged_ = false;
  bool landed_ = true;
  double first_state_t_ = -1.0;   ///< [s] the first state's time; < 0: none yet
  bool range_seen_ = false;       ///< a rangefinder reading came
  std::optional<double> range_;   ///< [m] the newest, none: nothing in range
  double still_since_ = -1.0;  ///< [s] the landing conditions have held since; < 0: they do not
};

}  // namespace quad::control
