// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Thrust and torques to rotor speeds, inverting the vehicle's allocation matrix, with
/// saturation handled in order of importance: roll and pitch torque first (they keep the
/// vehicle upright), then collective thrust (it keeps the altitude), then yaw torque (as
/// PX4's mixer does: rotor drag gives a quadrotor little yaw authority, and a yaw demand
/// that took thrust would sink the vehicle in every turn). Saturation is reported.

#include <array>

#include "quad/control/geometric_controller.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace quad::control {

struct MixerOutput {
  std::array<double, vehicle::kRotorCount> rotor_speed{};  ///< [rad/s], within the rotor limits
  bool saturated = false;        ///< anything was given up
  bool thrust_limited = false;   ///< collective thrust moved to make room
  double roll_pitch_scale = 1.0; ///< fraction of the roll/pitch torque delivered
  double yaw_scale = 1.0;        ///< fraction of the yaw torque delivered
  double thrust = 0.0;           ///< [N] delivered
  Vector3 torque_B = Vector3::Zero();  ///< [N m] delivered
};

class Mixer {
public:
  explicit Mixer(const vehicle::VehicleParams& vehicle);

  /// Rotor speeds for `thrust` [N] and `torque_B` [N m]. Non-finite inputs give the hover
  /// thrust with no torque, flagged as saturated (the caller also counts them).
  MixerOutput mix(double thrust, const Vector3& torque_B) const;

private:
  Eigen::Matrix4d allocation_;
  Eigen::Matrix4d inverse_;
  double min_;  // squared rotor speed limits
  double max_;
  double hover_thrust_;
};

}  // namespace quad::control
