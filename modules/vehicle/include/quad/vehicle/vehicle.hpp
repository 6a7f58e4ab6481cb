// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The quadrotor's physical description, shared by the plant (which simulates it) and the
/// controller (which inverts it): mass, inertia, rotor layout and constants, motor dynamics.
/// Declared once as a parameter schema; files live in configs/vehicles/*.yaml.
///
/// Layout: X configuration in the body frame (FLU: x forward, y left, z up). Rotors in
/// ActuatorCommand order: 0 front-left, 1 rear-left, 2 rear-right, 3 front-right, each at
/// arm_length from the centre on the diagonals. Rotors 0 and 2 spin counter-clockwise seen
/// from above (their reaction torque on the body is −z), 1 and 3 clockwise (+z).

#include <array>

#include <Eigen/Core>

#include "quad/common/param_table.hpp"

namespace quad::vehicle {

inline constexpr int kRotorCount = 4;

struct VehicleParams {
  double mass = 1.0;                                    ///< [kg]
  Eigen::Vector3d inertia = {0.01, 0.01, 0.02};         ///< [kg m²] principal moments, body axes
  double arm_length = 0.2;                              ///< [m] centre to rotor axis
  double thrust_coefficient = 8.5e-6;                   ///< k_f [N s²/rad²]: thrust = k_f ω²
  double torque_coefficient = 1.4e-7;                   ///< k_m [N m s²/rad²]: |reaction| = k_m ω²
  double rotor_speed_min = 0.0;                         ///< [rad/s]
  double rotor_speed_max = 1000.0;                      ///< [rad/s]
  double motor_time_constant_up = 0.02;                 ///< [s] first-order lag when speeding up
  double motor_time_constant_down = 0.04;               ///< [s] ... when slowing down
  Eigen::Vector3d drag_linear = {0.0, 0.0, 0.0};        ///< [N s/m] per body axis
  Eigen::Vector3d drag_quadratic = {0.0, 0.0, 0.0};     ///< [N s²/m²] per body axis
  double radius = 0.3;                                  ///< [m] bounding sphere, for collisions and planning

  /// Rotor positions in the body frame [m].
  std::array<Eigen::Vector3d, kRotorCount> rotorPositions() const;
  /// +1 for counter-clockwise rotors (0, 2), −1 for clockwise (1, 3).
  static constexpr std::array<double, kRotorCount> kSpin = {1.0, -1.0, 1.0, -1.0};

  /// A maps squared rotor speeds to [thrust (N, +z body); torque x, y, z (N m, body)].
  Eigen::Matrix4d allocation() const;

  /// [rad/s] rotor speed at which the four rotors together carry the weight.
  double hoverRotorSpeed(double gravity = 9.81) const;
};

/// configs/vehicles/*.yaml: every key with its unit, range and the field it fills; the
/// defaults are VehicleParams' own (the rest are required).
const common::ParamTable<VehicleParams>& vehicleTable();
common::ParamSchema vehicleSchema();

/// Reads validated params into VehicleParams; throws common::ConfigError (naming the
/// origin) when the values contradict each other (e.g. min speed above max, or the rotors at
/// full speed cannot lift the vehicle).
VehicleParams vehicleFromParams(const common::Params& params);

/// loadParams + vehicleFromParams.
VehicleParams loadVehicle(const std::filesystem::path& file);

}  // namespace quad::vehicle
