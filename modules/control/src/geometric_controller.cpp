// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/geometric_controller.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "quad/geometry/distance.hpp"

namespace quad::control {

GeometricController::GeometricController(double mass, const Vector3& inertia, const GeometricGains& gains,
                                         double gravity)
    : mass_(mass), inertia_(inertia), gains_(gains), gravity_(gravity)
{
  const bool ok = mass > 0.0 && (inertia.array() > 0.0).all() && gains.kx > 0.0 && gains.kv > 0.0 &&
                  gains.ki >= 0.0 && gains.integral_limit >= 0.0 &&
                  gains.kR > 0.0 && gains.kOmega > 0.0 && gains.yaw_weight > 0.0 && gains.yaw_weight <= 1.0 &&
                  gains.max_tilt > 0.0 && gains.max_tilt < geometry::kPi / 2.0 && (gains.max_rate.array() > 0.0).all();
  if (!ok) {
    throw std::invalid_argument(
        "GeometricController: mass, inertia, gains, max_tilt (0, pi/2) and max_rate must be positive, "
        "yaw_weight in (0, 1], the integral gain and limit not negative");
  }
}

namespace {
/// [s] the time constant Ω_d is smoothed with.
constexpr double kDesiredRateLag = 0.02;
}  // namespace

Matrix3 GeometricController::desiredAttitude(const Vector3& thrust_W, double yaw)
{
  const Vector3 b3 = thrust_W.normalized();
  const Vector3 b1c(std::cos(yaw), std::sin(yaw), 0.0);
  Vector3 b2 = b3.cross(b1c);
  const double n = b2.norm();
  if (n < 1e-3) {
    // The thrust direction is (nearly) the heading: b1c no longer fixes the yaw. Keep the
    // previous b2, made orthogonal to b3.
    b2 = previous_b2_ - previous_b2_.dot(b3) * b3;
    if (b2.norm() < 1e-6) {
      b2 = b3.unitOrthogonal();
    }
  }
  b2.normalize();
  previous_b2_ = b2;
  Matrix3 R;
  R.col(0) = b2.cross(b3);
  R.col(1) = b2;
  R.col(2) = b3;
  return R;
}

namespace {
bool finite(const VehicleState& s)
{
  const double n = s.q_WB.norm();
  return s.p_W.allFinite() && s.v_W.allFinite() && s.w_B.allFinite() && std::isfinite(n) &&
         std::abs(n - 1.0) < 1e-3;
}

bool finite(const Reference& r)
{
  return r.p_W.allFinite() && r.v_W.allFinite() && r.a_W.allFinite() && r.j_W.allFinite() && std::isfinite(r.yaw) &&
         std::isfinite(r.yaw_rate);
}
}  // namespace

ControlOutput GeometricController::invalidOutput() const
{
  ControlOutput invalid;
  invalid.valid = false;
  invalid.thrust = mass_ * gravity_;
  return invalid;
}

ControlOutput GeometricController::update(const VehicleState& s, const Reference& ref, double dt)
{
  if (!finite(s) || !finite(ref) || !std::isfinite(dt)) {
    return invalidOutput();
  }
  const Vector3 e3 = Vector3::UnitZ();
  const Vector3 e_x = s.p_W - ref.p_W;
  const Vector3 e_v = s.v_W - ref.v_W;
  // Feedback acceleration, limited horizontally: a distant reference must not tip it over.
  Vector3 a_fb = (-gains_.kx * e_x - gains_.kv * e_v + integralForce()) / mass_;
  const double horizontal = a_fb.head<2>().norm();
  const bool horizontal_limited = horizontal > gains_.max_acceleration;
  if (horizontal_limited) {
    a_fb.head<2>() *= gains_.max_acceleration / horizontal;
  }
  Vector3 thrust_W = mass_ * (a_fb + ref.a_W + gravity_ * e3);
  // Tilt limit: keep the vertical part, shorten the horizontal part. Never push downwards.
  const bool vertical_limited = thrust_W.z() < 0.1 * mass_ * gravity_;
  thrust_W.z() = std::max(thrust_W.z(), 0.1 * mass_ * gravity_);
  const double max_horizontal = thrust_W.z() * std::tan(gains_.max_tilt);
  const double h = thrust_W.head<2>().norm();
  const bool tilt_limited = h > max_horizontal;
  if (tilt_limited) {
    thrust_W.head<2>() *= max_horizontal / h;
  }
  if (!thrust_W.allFinite()) {
    return invalidOutput();  // finite inputs so far apart that the feedback overflows
  }
  // Anti-windup: an axis whose command was cut short does not integrate (the error there is
  // the limit's, not the model's), and the integral's force stays within its limit.
  if (integrating_ && gains_.ki > 0.0 && dt > 0.0) {
    const bool hold_horizontal = horizontal_limited || tilt_limited;
    const Vector3 step(hold_horizontal ? 0.0 : e_x.x() * dt, hold_horizontal ? 0.0 : e_x.y() * dt,
                       vertical_limited ? 0.0 : e_x.z() * dt);
    const double bound = gains_.integral_limit / gains_.ki;
    integral_ = (integral_ + step).cwiseMax(-bound).cwiseMin(bound);
  }
  const Matrix3 R_WD = desiredAttitude(thrust_W, ref.yaw);
  // Ω_d from the change of the desired attitude since the last tick (the feed-forward
  // acceleration's, its jerk on a trajectory, and the feedback's), plus the yaw rate, smoothed
  // over kDesiredRateLag: differenced tick by tick it turns a state's noise (2 cm at 250 Hz)
  // into rates at their limit, and the saturated rotors let the vehicle sink.
  Vector3 w_D = Vector3(0.0, 0.0, ref.yaw_rate);
  if (have_previous_ && dt > 0.0) {
    const Vector3 w = geometry::logSO3(previous_R_WD_.transpose() * R_WD) / dt;
    w_D_ += (dt / (kDesiredRateLag + dt)) * (w.cwiseMax(-gains_.max_rate).cwiseMin(gains_.max_rate) - w_D_);
    w_D = w_D_;
  }
  previous_R_WD_ = R_WD;
  have_previous_ = true;
  const Matrix3 R = geometry::toMatrix(s.q_WB);
  // f = F_des · R e3: the thrust the current attitude can put along the desired vector.
  const double thrust = std::max(0.0, thrust_W.dot(R * e3));
  return updateAttitude(s, R_WD, thrust, w_D);
}

ControlOutput GeometricController::updateAttitude(const VehicleState& s, const Matrix3& R_WD, double thrust,
                                                  const Vector3& w_D_B)
{
  if (!finite(s) || !R_WD.allFinite() || !std::isfinite(thrust) || !w_D_B.allFinite()) {
    return invalidOutput();
  }
  const Matrix3 R = geometry::toMatrix(s.q_WB);
  ControlOutput out;
  out.thrust = thrust;
  out.R_WD = R_WD;
  // e_R = ½ vee(R_dᵀ R − Rᵀ R_d) or 2 sgn(q_w) q_v of R_dᵀ R; e_Ω = Ω − Rᵀ R_d Ω_d
  const Matrix3 R_DB = R_WD.transpose() * R;
  if (gains_.attitude_error == AttitudeError::kQuaternion) {
    out.e_R = 2.0 * geometry::fromMatrix(R_DB).canonical().imaginary();
  } else {
    out.e_R = 0.5 * geometry::vee(R_DB - R_DB.transpose());
  }
  const Vector3 w_D_in_B = R.transpose() * R_WD * w_D_B;
  out.e_Omega = s.w_B - w_D_in_B;
  out.attitude_error = geometry::geodesicAngle(R, R_WD);
  // Tilt before yaw: the yaw component of the error counts with yaw_weight.
  const Vector3 e_R_weighted(out.e_R.x(), out.e_R.y(), gains_.yaw_weight * out.e_R.z());
  // M = −kR e_R − kΩ e_Ω + Ω × JΩ, written as a rate loop around the attitude error so the
  // rate it asks for can be limited: −kΩ (Ω − Ω_cmd) with Ω_cmd = Ω_d − (kR/kΩ) e_R.
  const Vector3 w_cmd = (w_D_in_B - (gains_.kR / gains_.kOmega) * e_R_weighted)
                            .cwiseMax(-gains_.max_rate)
                            .cwiseMin(gains_.max_rate);
  const Vector3 Jw = inertia_.cwiseProduct(s.w_B);
  // ... and Lee's −J(Ω̂ Rᵀ R_d Ω_d) term (Ω̇_d is taken as zero).
  out.torque_B = -gains_.kOmega * (s.w_B - w_cmd) + s.w_B.cross(Jw) -
                 inertia_.cwiseProduct(s.w_B.cross(w_D_in_B));
  return out;
}

}  // namespace quad::control
