// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Dead reckoning across a gap in the vehicle state: the last state received, carried on by
/// the IMU (angular rate turns the attitude, specific force rotated into the world plus
/// gravity moves the velocity and position). It lets a failsafe landing brake and hold its
/// place while the state is gone, instead of descending blind on its momentum. Errors grow
/// with time (bias: quadratically in position), so an estimate is given only for a bounded
/// horizon after the last state.

#include <optional>

#include "quad/control/geometric_controller.hpp"

namespace quad::control {

/// One IMU sample: body frame (FLU), as the sensor reports it.
struct InertialSample {
  Vector3 specific_force_B = Vector3::Zero();  ///< [m/s²] R_WBᵀ (a_W − g_W): +g z at rest
  Vector3 angular_rate_B = Vector3::Zero();    ///< [rad/s]
};

class DeadReckoning {
public:
  explicit DeadReckoning(double gravity = 9.81) : gravity_(gravity) {}

  /// A measured state at time t [s]: the estimate restarts from it.
  void anchor(const VehicleState& state, double t);

  /// An IMU sample taken at time t [s]: integrates the estimate from its time to t, holding
  /// the sample over the interval. Returns false (nothing changes) for a non-finite sample or time, or a
  /// rotation too large to represent.
  /// Samples at or before the estimate's time are ignored (the anchor already holds them).
  bool onImu(const InertialSample& sample, double t);

  /// The estimate (at time()) for use at time t [s]: given when there is an anchor, the IMU
  /// has carried it to within `max_imu_gap` [s] of t, and t is within `horizon` [s] of the
  /// anchor.
  std::optional<VehicleState> estimate(double t, double max_imu_gap, double horizon) const;

  /// [s] the time of the estimate (the last anchor or IMU sample applied); < 0 without one.
  double time() const { return t_; }

private:
  double gravity_;
  std::optional<VehicleState> state_;
  double anchor_t_ = -1.0;
  double t_ = -1.0;
};

}  // namespace quad::control
