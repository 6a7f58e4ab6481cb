// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Geometric tracking control on SE(3): Lee, Leok & McClamroch, "Geometric tracking control
/// of a quadrotor UAV on SE(3)", CDC 2010. The position loop turns position and velocity
/// errors plus the feed-forward acceleration into a desired thrust vector; the desired
/// attitude has that vector as its z axis and the reference heading as its x axis; the
/// attitude loop on SO(3) gives the body torques. Tilt has priority over yaw through a yaw
/// weight on the attitude error (as PX4 does after Brescianini et al., 2013), and the rates
/// the attitude loop asks for are limited.
///
/// Frames: world ENU (z up, gravity −g z), body FLU. Configured once, then stepped with the
/// state and reference of each tick; time enters as an argument.

#include "quad/geometry/quaternion.hpp"

namespace quad::control {

using geometry::Matrix3;
using geometry::Quaternion;
using geometry::Vector3;

struct VehicleState {
  Vector3 p_W = Vector3::Zero();  ///< [m]
  Vector3 v_W = Vector3::Zero();  ///< [m/s]
  Quaternion q_WB;
  Vector3 w_B = Vector3::Zero();  ///< [rad/s]
};

struct Reference {
  Vector3 p_W = Vector3::Zero();  ///< [m]
  Vector3 v_W = Vector3::Zero();  ///< [m/s]
  Vector3 a_W = Vector3::Zero();  ///< [m/s²] feed-forward
  double yaw = 0.0;               ///< [rad] heading of body x about world z
  double yaw_rate = 0.0;          ///< [rad/s] feed-forward
  /// [m/s³] the feed-forward acceleration's rate: it turns the desired thrust direction, and
  /// so the desired attitude, whose rate Ω_d the attitude loop feeds forward (update())
  Vector3 j_W = Vector3::Zero();
};

/// How the attitude error e_R is formed from R_dᵀR, a rotation by θ about an axis a.
enum class AttitudeError {
  /// e_R = ½ vee(R_dᵀR − RᵀR_d) = sin θ a (Lee et al. 2010). It fades near θ = 180°, so a
  /// vehicle upside down leaves slowly: with the paper's gains, 2.5 s from 178° to 1°.
  kLee2010,
  /// e_R = 2 sgn(q_w) q_v for the error quaternion q of R_dᵀR, = 2 sin(θ/2) a: the gradient
  /// of Lee's 2012 error function 2(2 − √(1 + tr R_dᵀR)), the error PX4 uses. Equal to the
  /// 2010 error to first order near θ = 0, at its largest (2) near 180°.
  kQuaternion,
};

struct GeometricGains {
  double kx = 16.0;       ///< [N/m] position
  double kv = 5.6;        ///< [N s/m] velocity
  double kR = 8.81;       ///< [N m/rad] attitude
  double kOmega = 2.54;   ///< [N m s/rad] angular rate
  double yaw_weight = 0.4;  ///< (0, 1]: yaw error's share of the attitude error
  double max_tilt = 0.6;    ///< [rad] desired thrust vector at most this far from vertical
  Vector3 max_rate{6.0, 6.0, 2.0};  ///< [rad/s] body rates the attitude loop may ask for
  double max_acceleration = 8.0;    ///< [m/s²] horizontal feedback acceleration limit
  /// [N/(m s)] k_i: the position error's integral, for what the model leaves out (a mass
  /// off its file, steady wind). 0: none.
  double ki = 0.0;
  double integral_limit = 5.0;      ///< [N] the most force the integral adds on each axis
  AttitudeError attitude_error = AttitudeError::kQuaternion;
};

struct ControlOutput {
  /// False when the inputs were not finite (or the attitude not a unit quaternion): then
  /// the output is the hover thrust with no torque, and the caller must not trust it.
  bool valid = true;
  double thrust = 0.0;            ///< [N] collective, along body z
  Vector3 torque_B = Vector3::Zero();  ///< [N m]
  Matrix3 R_WD = Matrix3::Identity();  ///< desired attitude
  Vector3 e_R = Vector3::Zero();  ///< attitude error (unweighted)
  Vector3 e_Omega = Vector3::Zero();
  double attitude_error = 0.0;    ///< [rad] geodesic angle between desired and actual
};

class GeometricController {
public:
  /// `mass` [kg], `inertia` [kg m²] principal moments. Throws std::invalid_argument on
  /// non-positive mass, inertia or gains, or yaw_weight outside (0, 1].
  GeometricController(double mass, const Vector3& inertia, const GeometricGains& gains,
                      double gravity = 9.81);

  /// Position and attitude control (the full SE(3) controller). Never throws: invalid
  /// inputs give an output marked invalid.
  ControlOutput update(const VehicleState& state, const Reference& ref, double dt);

  /// Attitude only: hold `R_WD` with thrust `thrust` (Lee's attitude-controlled flight mode).
  ControlOutput updateAttitude(const VehicleState& state, const Matrix3& R_WD, double thrust,
                               const Vector3& w_D_B = Vector3::Zero());

  /// Forget the previous desired attitude (used for Ω_d by finite differences) and the
  /// position error's integral.
  void reset()
  {
    have_previous_ = false;
    w_D_.setZero();
    integral_.setZero();
  }
  /// Whether update() integrates the position error (the integral itself is kept when not):
  /// off where the error is not the model's fault (on the ground, taking off, landing).
  void integrate(bool on) { integrating_ = on; }
  /// [N] the force the integral adds now.
  Vector3 integralForce() const { return -gains_.ki * integral_; }

  const GeometricGains& gains() const { return gains_; }

private:
  Matrix3 desiredAttitude(const Vector3& thrust_W, double yaw);
  /// The flagged hover output for inputs it cannot use.
  ControlOutput invalidOutput() const;

  double mass_;
  Vector3 inertia_;
  GeometricGains gains_;
  double gravity_;
  Matrix3 previous_R_WD_ = Matrix3::Identity();
  Vector3 previous_b2_ = Vector3::UnitY();
  bool have_previous_ = false;
  Vector3 w_D_ = Vector3::Zero();  ///< [rad/s] Ω_d, smoothed
  Vector3 integral_ = Vector3::Zero();  ///< [m s] ∫ e_x dt
  bool integrating_ = true;
};

}  // namespace quad::control
