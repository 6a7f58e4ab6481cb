// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Closed-form motions flown past the plant's sensor models, fed to a filter in time order.

#include <cmath>
#include <deque>
#include <functional>
#include <random>

#include "quad/estimation/error_state_filter.hpp"
#include "quad/geometry/quaternion.hpp"
#include "quad/plant/navigation_sensors.hpp"
#include "quad/plant/sensors.hpp"

namespace quad::estimation::test {

/// The truth at a time.
struct Truth {
  Vector3 p_W = Vector3::Zero();
  Vector3 v_W = Vector3::Zero();
  Vector3 a_W = Vector3::Zero();
  Matrix3 R_WB = Matrix3::Identity();
  Vector3 w_B = Vector3::Zero();
};

using Motion = std::function<Truth(double t)>;

/// A straight line at a constant velocity, yawed `yaw`.
inline Motion constantVelocity(const Vector3& p0, const Vector3& v, double yaw)
{
  return [=](double t) {
    Truth x;
    x.p_W = p0 + v * t;
    x.v_W = v;
    x.R_WB = geometry::rotZ(yaw);
    return x;
  };
}

/// A level circle of radius `r` at speed `speed` around `centre`, nose along the velocity.
inline Motion coordinatedTurn(const Vector3& centre, double r, double speed)
{
  return [=](double t) {
    const double w = speed / r;
    const double a = w * t;
    Truth x;
    x.p_W = centre + Vector3(r * std::cos(a), r * std::sin(a), 0.0);
    x.v_W = Vector3(-std::sin(a), std::cos(a), 0.0) * speed;
    x.a_W = -Vector3(std::cos(a), std::sin(a), 0.0) * speed * w;
    x.R_WB = geometry::rotZ(a + M_PI / 2);
    x.w_B = Vector3(0.0, 0.0, w);
    return x;
  };
}

/// The same circle, entered from rest: the speed rises as 1 − e^(−t/τ) (a vehicle aligned on
/// the ground, then flying).
inline Motion spinUpTurn(const Vector3& centre, double r, double speed, double tau)
{
  return [=](double t) {
    const double w = speed / r;
    const double e = std::exp(-t / tau);
    const double a = w * (t - tau + tau * e);
    const double a_dot = w * (1.0 - e);
    const double a_ddot = w / tau * e;
    const Vector3 radial(std::cos(a), std::sin(a), 0.0);
    const Vector3 tangent(-std::sin(a), std::cos(a), 0.0);
    Truth x;
    x.p_W = centre + r * radial;
    x.v_W = r * a_dot * tangent;
    x.a_W = r * a_ddot * tangent - r * a_dot * a_dot * radial;
    x.R_WB = geometry::rotZ(a + M_PI / 2);
    x.w_B = Vector3(0.0, 0.0, a_dot);
    return x;
  };
}

struct Sensors {
  plant::ImuConfig imu;
  plant::ImuBias bias;  ///< held constant unless walk is set
  bool walk = false;
  plant::PositionSensorConfig position;
  plant::BarometerConfig baro;
  plant::MagnetometerConfig mag;
  Vector3 mag_disturbance_W = Vector3::Zero();
  Vector3 gravity_W{0.0, 0.0, -9.81};
};

/// Flies `motion` for `seconds`, feeding `filter` the sensors' samples in time order (IMU at
/// its rate, fixes their latency late, barometer and magnetometer at theirs); `each` runs
/// after every IMU sample with the time [s] and the truth then. `hook` may change the
/// sensors between samples (faults).
template <class Filter>
void fly(Filter& filter, const Motion& motion, double seconds, Sensors sensors, std::uint64_t seed,
         const std::function<void(double, const Truth&)>& each = {},
         const std::function<void(double, Sensors&)>& hook = {})
{
  std::mt19937_64 rng(seed);
  plant::PositionSensor position(sensors.position);
  plant::Barometer baro(sensors.baro, rng);
  const std::int64_t imu_period = static_cast<std::int64_t>(std::llround(1e9 / sensors.imu.rate_hz));
  const auto every = [&](double hz) { return static_cast<std::int64_t>(std::llround(1e9 / hz)); };
  const std::int64_t latency = static_cast<std::int64_t>(std::llround(sensors.position.latency * 1e9));
  std::deque<std::pair<std::int64_t, plant::PositionFix>> in_flight;
  const std::int64_t end = static_cast<std::int64_t>(std::llround(seconds * 1e9));
  for (std::int64_t t = imu_period; t <= end; t += imu_period) {
    const double ts = static_cast<double>(t) * 1e-9;
    if (hook) {
      hook(ts, sensors);
    }
    const Truth x = motion(ts);
    const geometry::Quaternion q = geometry::fromMatrix(x.R_WB);
    if (sensors.walk) {
      plant::walkBias(sensors.bias, sensors.imu, 1.0 / sensors.imu.rate_hz, rng);
    }
    const plant::ImuSample s = plant::measureImu(sensors.imu, sensors.bias, q, x.a_W, x.w_B, sensors.gravity_W, rng);
    filter.imu(t, s.specific_force_B, s.angular_rate_B);
    if (sensors.position.enabled && t % every(sensors.position.rate_hz) == 0) {
      if (const auto fix = position.measure(x.p_W, rng)) {
        in_flight.emplace_back(t, *fix);
      }
    }
    while (!in_flight.empty() && in_flight.front().first + latency <= t) {
      filter.position(in_flight.front().first, in_flight.front().second.p_W, in_flight.front().second.std_dev);
      in_flight.pop_front();
    }
    if (sensors.baro.enabled && t % every(sensors.baro.rate_hz) == 0) {
      filter.baro(t, baro.measure(x.p_W.z(), 1.0 / sensors.baro.rate_hz, rng), sensors.baro.noise_std);
    }
    if (sensors.mag.enabled && t % every(sensors.mag.rate_hz) == 0) {
      filter.mag(t, plant::measureMagnetometer(sensors.mag, q, sensors.mag_disturbance_W, rng), sensors.mag.noise_std);
    }
    if (each) {
      each(ts, x);
    }
  }
}

/// The attitude error [rad] of an estimate, in the world frame (the filter's δθ).
inline Vector3 attitudeError(const Truth& x, const Estimate& e)
{
  return MrptRotations::log(x.R_WB * geometry::toMatrix(e.q_WB).transpose());
}

}  // namespace quad::estimation::test
