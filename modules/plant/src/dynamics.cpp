// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace quad::plant {

namespace {

RigidBodyState advance(const RigidBodyState& s, const Vector3& dp, const Vector3& dv,
                       const Quaternion& dq, const Vector3& dw, const RotorArray& dr, double h)
{
  RigidBodyState out = s;
  out.p_W += h * dp;
  out.v_W += h * dv;
  out.q_WB = {s.q_WB.w + h * dq.w, s.q_WB.x + h * dq.x, s.q_WB.y + h * dq.y, s.q_WB.z + h * dq.z};
  out.w_B += h * dw;
  for (std::size_t i = 0; i < dr.size(); ++i) {
    out.rotor_speed[i] += h * dr[i];
  }
  return out;
}

/// The attitude with its tilt removed: the vehicle rests flat on the ground, keeping its yaw.
Quaternion levelled(const Quaternion& q)
{
  const Vector3 forward = geometry::toMatrix(q).col(0);
  const double yaw = std::atan2(forward.y(), forward.x());
  return {std::cos(yaw / 2.0), 0.0, 0.0, std::sin(yaw / 2.0)};
}

}  // namespace

QuadrotorDynamics::QuadrotorDynamics(vehicle::VehicleParams params)
    : params_(std::move(params)), allocation_(params_.allocation()), inertia_(params_.inertia)
{
}

Wrench QuadrotorDynamics::wrench(const RigidBodyState& s, const Environment& env) const
{
  Eigen::Vector4d w2;
  for (int i = 0; i < vehicle::kRotorCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    w2[i] = env.rotor_efficiency[k] * s.rotor_speed[k] * s.rotor_speed[k];
  }
  const Eigen::Vector4d ft = allocation_ * w2;
  Wrench out;
  out.force_B = Vector3(0.0, 0.0, ft[0]);
  out.torque_B = ft.tail<3>();
  // Drag against the air, per body axis: −D₁ v − D₂ |v| v.
  const Vector3 v_air_B = geometry::toMatrix(s.q_WB).transpose() * (s.v_W - env.wind_W);
  out.force_B -= params_.drag_linear.cwiseProduct(v_air_B) +
                 params_.drag_quadratic.cwiseProduct(v_air_B.cwiseAbs().cwiseProduct(v_air_B));
  return out;
}

QuadrotorDynamics::Derivative QuadrotorDynamics::derivative(const RigidBodyState& s,
                                                            const RotorArray& commanded,
                                                            const Environment& env) const
{
  Derivative d;
  const Wrench f = wrench(s, env);
  const geometry::Matrix3 R = geometry::toMatrix(s.q_WB);
  d.dp = s.v_W;
  d.dv = (R * f.force_B + env.force_W) / params_.mass + env.gravity_W;
  // q̇ = ½ q ⊗ (0, ω_B)
  const Quaternion half = s.q_WB * Quaternion{0.0, s.w_B.x(), s.w_B.y(), s.w_B.z()};
  d.dq = {0.5 * half.w, 0.5 * half.x, 0.5 * half.y, 0.5 * half.z};
  // J ω̇ = τ − ω × J ω (Euler's equations, principal axes)
  const Vector3 Jw = inertia_.cwiseProduct(s.w_B);
  d.dw = (f.torque_B - s.w_B.cross(Jw)).cwiseQuotient(inertia_);
  for (std::size_t i = 0; i < commanded.size(); ++i) {
    // A sagging supply lowers the top speed, below the minimum when it is gone.
    const double target =
        std::min(std::max(commanded[i], params_.rotor_speed_min), env.supply * params_.rotor_speed_max);
    const double tau = target > s.rotor_speed[i] ? params_.motor_time_constant_up
                                                 : params_.motor_time_constant_down;
    d.drotor[i] = (target - s.rotor_speed[i]) / tau;
  }
  return d;
}

void QuadrotorDynamics::step(RigidBodyState& s, const RotorArray& commanded,
                             const Environment& env, double dt) const
{
  const Derivative k1 = derivative(s, commanded, env);
  const Derivative k2 = derivative(advance(s, k1.dp, k1.dv, k1.dq, k1.dw, k1.drotor, dt / 2), commanded, env);
  const Derivative k3 = derivative(advance(s, k2.dp, k2.dv, k2.dq, k2.dw, k2.drotor, dt / 2), commanded, env);
  const Derivative k4 = derivative(advance(s, k3.dp, k3.dv, k3.dq, k3.dw, k3.drotor, dt), commanded, env);
  const auto mix = [](const auto& a, const auto& b, const auto& c, const auto& d) {
    return (a + 2.0 * b + 2.0 * c + d) / 6.0;
  };
  const Quaternion dq{mix(k1.dq.w, k2.dq.w, k3.dq.w, k4.dq.w), mix(k1.dq.x, k2.dq.x, k3.dq.x, k4.dq.x),
                      mix(k1.dq.y, k2.dq.y, k3.dq.y, k4.dq.y), mix(k1.dq.z, k2.dq.z, k3.dq.z, k4.dq.z)};
  RotorArray dr{};
  for (std::size_t i = 0; i < dr.size(); ++i) {
    dr[i] = mix(k1.drotor[i], k2.drotor[i], k3.drotor[i], k4.drotor[i]);
  }
  const RigidBodyState before = s;
  s = advance(s, mix(k1.dp, k2.dp, k3.dp, k4.dp), mix(k1.dv, k2.dv, k3.dv, k4.dv), dq,
              mix(k1.dw, k2.dw, k3.dw, k4.dw), dr, dt);
  s.q_WB = s.q_WB.normalized();
  for (double& w : s.rotor_speed) {
    w = std::clamp(w, params_.rotor_speed_min, params_.rotor_speed_max);
  }
  if (before.landed) {
    // While landed the body stays put unless the thrust's vertical part beats gravity.
    const Vector3 thrust_W = geometry::toMatrix(before.q_WB) * wrench(s, env).force_B;
    if (thrust_W.z() + params_.mass * env.gravity_W.z() <= 0.0) {
      const RotorArray rotors = s.rotor_speed;
      s = before;
      s.rotor_speed = rotors;
      return;
    }
    s.landed = false;
  }
  resolveGround(s, env);
}

void QuadrotorDynamics::resolveGround(RigidBodyState& s, const Environment& env) const
{
  if (s.p_W.z() > env.ground_z) {
    return;
  }
  // Touchdown within this step: stop on the surface instead of passing through it.
  s.p_W.z() = env.ground_z;
  s.v_W.setZero();
  s.w_B.setZero();
  s.q_WB = levelled(s.q_WB);
  const Vector3 thrust_W = geometry::toMatrix(s.q_WB) * wrench(s, env).force_B;
  s.landed = thrust_W.z() + params_.mass * env.gravity_W.z() <= 0.0;
}

Vector3 QuadrotorDynamics::acceleration(const RigidBodyState& s, const Environment& env) const
{
  if (s.landed) {
    return Vector3::Zero();
  }
  return geometry::toMatrix(s.q_WB) * wrench(s, env).force_B / params_.mass + env.gravity_W;
}

Vector3 QuadrotorDynamics::angularMomentum_W(const RigidBodyState& s) const
{
  return geometry::toMatrix(s.q_WB) * inertia_.cwiseProduct(s.w_B);
}

double QuadrotorDynamics::kineticEnergy(const RigidBodyState& s) const
{
  return 0.5 * params_.mass * s.v_W.squaredNorm() + 0.5 * s.w_B.dot(inertia_.cwiseProduct(s.w_B));
}

}  // namespace quad::plant
