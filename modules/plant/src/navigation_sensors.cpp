// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/navigation_sensors.hpp"

#include <algorithm>
#include <cmath>

#include "quad/geometry/quaternion.hpp"
#include "quad/plant/sensors.hpp"

namespace quad::plant {

std::optional<PositionFix> PositionSensor::measure(const Vector3& p_W, std::mt19937_64& rng, double extra_noise_std)
{
  const double period_s = 1.0 / config_.rate_hz;
  if (outage_left_s_ > 0.0) {
    outage_left_s_ -= period_s;
    return std::nullopt;
  }
  // An outage starts within this period with the Poisson process's probability.
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double rate_per_s = config_.outages_per_minute / 60.0;
  if (rate_per_s > 0.0 && u(rng) < 1.0 - std::exp(-rate_per_s * period_s)) {
    std::exponential_distribution<double> length(1.0 / config_.outage_duration);
    outage_left_s_ = length(rng);
    return std::nullopt;
  }
  const double std_dev = config_.noise_std + extra_noise_std;
  return PositionFix{p_W + std_dev * standardNormal3(rng), config_.noise_std};
}

Barometer::Barometer(BarometerConfig config, std::mt19937_64& rng) : config_(config)
{
  std::normal_distribution<double> n(0.0, 1.0);
  offset_ = config_.offset_std * n(rng);
}

double Barometer::measure(double z_W, double dt_s, std::mt19937_64& rng, double extra_noise_std)
{
  std::normal_distribution<double> n(0.0, 1.0);
  offset_ += config_.drift_walk * std::sqrt(dt_s) * n(rng);
  const double noise = n(rng);
  return z_W + offset_ + (config_.noise_std + extra_noise_std) * noise;
}

Vector3 measureMagnetometer(const MagnetometerConfig& config, const geometry::Quaternion& q_WB,
                            const Vector3& disturbance_W, std::mt19937_64& rng, double extra_noise_std)
{
  const geometry::Matrix3 R_WB = geometry::toMatrix(q_WB);
  return R_WB.transpose() * (config.field_W + disturbance_W) + (config.noise_std + extra_noise_std) * standardNormal3(rng);
}

std::optional<double> measureRange(const RangefinderConfig& config, const world::World& world, const Vector3& p_W,
                                   const geometry::Quaternion& q_WB, const Vector3& axis_B, std::mt19937_64& rng,
                                   double extra_noise_std)
{
  // Each looks from kRangefinderLift over the origin (the body's top): the downward one sees a
  // surface the origin touches, the upward one does not see the surface the body stands on.
  const geometry::Matrix3 R_WB = geometry::toMatrix(q_WB);
  const Vector3 axis_W = R_WB * axis_B;
  const double ahead = kRangefinderLift * axis_B.dot(kUpward);  // [m] where it looks from, along its axis
  const auto hit = world.raycast(p_W + kRangefinderLift * (R_WB * kUpward), axis_W, config.max_range - ahead);
  const double noise = (config.noise_std + extra_noise_std) * std::normal_distribution<double>(0.0, 1.0)(rng);
  if (!hit || hit->distance + ahead > config.max_range) {
    return std::nullopt;
  }
  return std::max(0.0, hit->distance + ahead + noise);
}

}  // namespace quad::plant
