// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/mixer.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace quad::control {

namespace {

/// The interval of t for which u + t·ones stays inside [lo, hi] on every rotor.
std::pair<double, double> shiftRange(const Eigen::Vector4d& u, double lo, double hi)
{
  return {lo - u.minCoeff(), hi - u.maxCoeff()};
}

}  // namespace

Mixer::Mixer(const vehicle::VehicleParams& v)
    : allocation_(v.allocation()),
      inverse_(allocation_.inverse()),
      min_(v.rotor_speed_min * v.rotor_speed_min),
      max_(v.rotor_speed_max * v.rotor_speed_max),
      hover_thrust_(v.mass * 9.81)
{
}

MixerOutput Mixer::mix(double thrust, const Vector3& torque_B) const
{
  MixerOutput out;
  if (!std::isfinite(thrust) || !torque_B.allFinite()) {
    out = mix(hover_thrust_, Vector3::Zero());
    out.saturated = true;
    return out;
  }
  // Squared speeds per unit of each channel: the columns of A⁻¹.
  const Eigen::Vector4d per_thrust = inverse_.col(0);  // uniform across rotors for an X layout
  const Eigen::Vector4d rp = inverse_.col(1) * torque_B.x() + inverse_.col(2) * torque_B.y();
  const Eigen::Vector4d yaw = inverse_.col(3) * torque_B.z();
  const double unit = per_thrust.mean();  // squared speed per newton, per rotor
  const double span = max_ - min_;

  // 1. Roll and pitch: shrink them only if even the best thrust cannot fit them.
  const double rp_spread = rp.maxCoeff() - rp.minCoeff();
  if (rp_spread > span) {
    out.roll_pitch_scale = span / rp_spread;
  }
  Eigen::Vector4d u = out.roll_pitch_scale * rp;
  // 2. Thrust: the requested collective if it fits beside roll and pitch, else the nearest
  //    that does. It comes before yaw: a quadrotor's yaw authority is weak (rotor drag), and
  //    a yaw demand that took thrust would make the vehicle sink in every turn.
  const double wanted = thrust * unit;
  const auto [t_lo, t_hi] = shiftRange(u, min_, max_);
  const double t = std::clamp(wanted, t_lo, std::max(t_lo, t_hi));
  out.thrust_limited = std::abs(t - wanted) > 1e-9 * std::max(1.0, std::abs(wanted));
  u.array() += t;
  // 3. Yaw: the largest share in [0, 1] that keeps every rotor within its limits.
  double s_max = 1.0;
  for (int i = 0; i < vehicle::kRotorCount; ++i) {
    if (yaw[i] > 0.0) {
      s_max = std::min(s_max, (max_ - u[i]) / yaw[i]);
    } else if (yaw[i] < 0.0) {
      s_max = std::min(s_max, (min_ - u[i]) / yaw[i]);
    }
  }
  out.yaw_scale = std::clamp(s_max, 0.0, 1.0);
  u += out.yaw_scale * yaw;
  out.saturated = out.thrust_limited || out.roll_pitch_scale < 1.0 || out.yaw_scale < 1.0;
  for (int i = 0; i < vehicle::kRotorCount; ++i) {
    out.rotor_speed[static_cast<std::size_t>(i)] = std::sqrt(std::clamp(u[i], min_, max_));
  }
  const Eigen::Vector4d delivered = allocation_ * u.cwiseMax(min_).cwiseMin(max_);
  out.thrust = delivered[0];
  out.torque_B = delivered.tail<3>();
  return out;
}

}  // namespace quad::control
