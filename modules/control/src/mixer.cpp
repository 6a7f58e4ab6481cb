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
  // 2. Yaw: as much as fits beside roll and pitch.
  const double yaw_room = span - out.roll_pitch_scale * rp_spread;
  const Eigen::Vector4d with_yaw = u + yaw;
  const double spread = with_yaw.maxCoeff() - with_yaw.minCoeff();
  if (spread > span + 1e-12) {
    // Largest s in [0, 1] with spread(u + s·yaw) <= span (spread is convex in s: bisect).
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (lo + hi);
      const Eigen::Vector4d t = u + mid * yaw;
      (t.maxCoeff() - t.minCoeff() <= span ? lo : hi) = mid;
    }
    out.yaw_scale = yaw_room > 0.0 ? lo : 0.0;
  }
  u += out.yaw_scale * yaw;
  // 3. Thrust: the requested collective if it fits, else the nearest that does.
  const double wanted = thrust * unit;
  const auto [t_lo, t_hi] = shiftRange(u, min_, max_);
  const double t = std::clamp(wanted, t_lo, std::max(t_lo, t_hi));
  out.thrust_limited = std::abs(t - wanted) > 1e-9 * std::max(1.0, std::abs(wanted));
  u.array() += t;
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
