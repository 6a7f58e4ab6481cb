// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Rigid-body dynamics of an X quadrotor: Newton–Euler with quaternion attitude, rotor thrust
/// and reaction torque (k_f ω², k_m ω²), first-order motor lag with separate up/down time
/// constants, linear and quadratic body drag against the air (wind), gravity, and ground
/// contact. Integrated with classical RK4; the quaternion is renormalized after every step.
///
/// Frames: world ENU (z up), body FLU. Time is an argument: the core never reads a clock.

#include <array>

#include "quad/geometry/quaternion.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace quad::plant {

using geometry::Quaternion;
using geometry::Vector3;
using RotorArray = std::array<double, vehicle::kRotorCount>;

struct RigidBodyState {
  Vector3 p_W = Vector3::Zero();       ///< [m] position, world
  Vector3 v_W = Vector3::Zero();       ///< [m/s] velocity, world
  Quaternion q_WB;                     ///< attitude, body → world
  Vector3 w_B = Vector3::Zero();       ///< [rad/s] angular velocity, body
  RotorArray rotor_speed{};            ///< [rad/s] actual rotor speeds
  bool landed = false;                 ///< resting on the surface beneath it (Environment::ground_z)
};

struct Environment {
  Vector3 gravity_W{0.0, 0.0, -9.81};  ///< [m/s²]
  Vector3 wind_W = Vector3::Zero();    ///< [m/s] air velocity, world
  Vector3 force_W = Vector3::Zero();   ///< [N] an external force on the body (a push), world
  /// Fraction of nominal thrust and torque each rotor delivers (1 healthy, 0 failed).
  RotorArray rotor_efficiency{1.0, 1.0, 1.0, 1.0};
  /// Fraction of the rated top rotor speed the battery's voltage allows (1: all of it).
  double supply = 1.0;
  /// [m] height of the surface beneath the vehicle, where it stands or touches down: the
  /// ground, a roof, a platform, an upper floor (world::World::supportHeight).
  double ground_z = 0.0;
};

/// Forces and torques on the body for a state, in the body frame.
struct Wrench {
  Vector3 force_B = Vector3::Zero();   ///< [N] rotor thrust + drag (gravity not included)
  Vector3 torque_B = Vector3::Zero();  ///< [N m]
};

class QuadrotorDynamics {
public:
  explicit QuadrotorDynamics(vehicle::VehicleParams params);

  const vehicle::VehicleParams& params() const { return params_; }

  /// Advances `state` by dt [s] towards the commanded rotor speeds (clamped to the rotor
  /// limits, the top one scaled by the supply; the motors follow with their lag). Resolves ground contact after the step: the
  /// vehicle never goes below the surface beneath it (env.ground_z); touching down stops it (inelastic, with friction) and
  /// sets `landed`; it stays landed until the thrust lifts it.
  void step(RigidBodyState& state, const RotorArray& commanded, const Environment& env,
            double dt) const;

  Wrench wrench(const RigidBodyState& state, const Environment& env) const;

  /// [m/s²] linear acceleration in the world frame, gravity included (zero while landed).
  Vector3 acceleration(const RigidBodyState& state, const Environment& env) const;

  /// Angular momentum in the world frame, R J ω [kg m²/s].
  Vector3 angularMomentum_W(const RigidBodyState& state) const;
  /// Kinetic (translational + rotational) energy [J].
  double kineticEnergy(const RigidBodyState& state) const;

private:
  struct Derivative {
    Vector3 dp, dv;
    Quaternion dq;
    Vector3 dw;
    RotorArray drotor;
  };
  Derivative derivative(const RigidBodyState& s, const RotorArray& commanded,
                        const Environment& env) const;
  void resolveGround(RigidBodyState& s, const Environment& env) const;

  vehicle::VehicleParams params_;
  Eigen::Matrix4d allocation_;
  Vector3 inertia_;
};

}  // namespace quad::plant
