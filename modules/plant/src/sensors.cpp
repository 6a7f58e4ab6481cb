// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/sensors.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "quad/geometry/so3.hpp"

namespace quad::plant {

DepthCamera::DepthCamera(DepthCameraConfig config)
    : config_(std::move(config)),
      q_BS_(geometry::fromAxisAngle(Vector3::UnitY(), config_.tilt_down))
{
  if (config_.width < 1 || config_.height < 1 || !(config_.max_range > 0.0) ||
      !(config_.horizontal_fov > 0.0 && config_.horizontal_fov < geometry::kPi)) {
    throw std::invalid_argument("DepthCamera: size, max range and field of view (0, pi) must be positive");
  }
  // Pinhole: pixel centres on the image plane x = 1.
  const double tan_h = std::tan(config_.horizontal_fov / 2.0);
  const double tan_v = tan_h * config_.height / config_.width;  // square pixels
  directions_.reserve(static_cast<std::size_t>(config_.width * config_.height));
  for (int v = 0; v < config_.height; ++v) {
    for (int u = 0; u < config_.width; ++u) {
      const double y = (0.5 - (u + 0.5) / config_.width) * 2.0 * tan_h;   // left positive
      const double z = (0.5 - (v + 0.5) / config_.height) * 2.0 * tan_v;  // up positive
      directions_.push_back(Vector3(1.0, y, z).normalized());
    }
  }
}

geometry::Pose3 DepthCamera::sensorPose(const geometry::Pose3& body_W) const
{
  return body_W * geometry::Pose3{config_.position_B, q_BS_};
}

DepthScan DepthCamera::capture(const world::World& world, const geometry::Pose3& body_W,
                               std::mt19937_64& rng, double extra_noise_std) const
{
  return captureFrom(world, sensorPose(body_W), rng, extra_noise_std);
}

DepthScan DepthCamera::captureFrom(const world::World& world, const geometry::Pose3& sensor_W,
                                   std::mt19937_64& rng, double extra_noise_std,
                                   std::span<const world::Sphere> others) const
{
  std::vector<world::Obstacle> bodies;
  bodies.reserve(others.size());
  for (const world::Sphere& s : others) {
    bodies.push_back(world::Obstacle::makeSphere(s));
  }
  DepthScan scan;
  scan.sensor_W = sensor_W;
  const geometry::Matrix3 R_WS = geometry::toMatrix(scan.sensor_W.q);
  const double noise_std = config_.noise_std + extra_noise_std;
  std::normal_distribution<double> noise(0.0, 1.0);
  scan.points_S.reserve(directions_.size());
  for (const Vector3& d_S : directions_) {
    const Vector3 d_W = R_WS * d_S;
    const auto hit = world.raycast(scan.sensor_W.p, d_W, config_.max_range);
    std::optional<double> nearest;
    if (hit) {
      nearest = hit->distance;
    }
    for (const world::Obstacle& body : bodies) {
      const auto t = body.raycast(scan.sensor_W.p, d_W, nearest.value_or(config_.max_range));
      if (t && (!nearest || *t < *nearest)) {
        nearest = t;
      }
    }
    double range = config_.max_range * kMissFactor;
    if (nearest) {
      range = std::max(0.0, *nearest + noise_std * noise(rng));
      ++scan.hits;
    }
    scan.points_S.push_back((d_S * range).cast<float>());
  }
  return scan;
}

Vector3 standardNormal3(std::mt19937_64& rng)
{
  std::normal_distribution<double> n(0.0, 1.0);
  // One at a time: argument evaluation order is unspecified, a run must repeat.
  const double x = n(rng);
  const double y = n(rng);
  const double z = n(rng);
  return Vector3(x, y, z);
}

ImuBias turnOnBias(const ImuConfig& config, std::mt19937_64& rng)
{
  ImuBias b;
  b.accel = config.accel_bias + config.accel_turn_on_std * standardNormal3(rng);
  b.gyro = config.gyro_bias + config.gyro_turn_on_std * standardNormal3(rng);
  return b;
}

void walkBias(ImuBias& bias, const ImuConfig& config, double dt_s, std::mt19937_64& rng)
{
  const double root_dt = std::sqrt(dt_s);
  bias.accel += config.accel_bias_walk * root_dt * standardNormal3(rng);
  bias.gyro += config.gyro_bias_walk * root_dt * standardNormal3(rng);
}

ImuSample measureImu(const ImuConfig& config, const ImuBias& bias, const geometry::Quaternion& q_WB, const Vector3& a_W,
                     const Vector3& w_B, const Vector3& gravity_W, std::mt19937_64& rng,
                     double extra_noise_std)
{
  return measureImuIntegrals(config, bias, geometry::toMatrix(q_WB).transpose() * (a_W - gravity_W), w_B, rng,
                             extra_noise_std);
}

ImuSample measureImuIntegrals(const ImuConfig& config, const ImuBias& bias, const Vector3& force_B, const Vector3& w_B,
                              std::mt19937_64& rng, double extra_noise_std)
{
  ImuSample out;
  out.specific_force_B = force_B + bias.accel + (config.accel_noise_std + extra_noise_std) * standardNormal3(rng);
  out.angular_rate_B = w_B + bias.gyro + (config.gyro_noise_std + extra_noise_std) * standardNormal3(rng);
  return out;
}

void ImuIntegrals::addStep(const geometry::Matrix3& R_WB_before, const Vector3& dv_W, const Vector3& gravity_W,
                           double dt_s)
{
  dv_B_ += R_WB_before.transpose() * (dv_W - gravity_W * dt_s);
  dt_s_ += dt_s;
}

std::optional<ImuIntegrals::Means> ImuIntegrals::sample(const geometry::Quaternion& q_WB)
{
  std::optional<Means> out;
  if (q_last_ && dt_s_ > 0.0) {
    const geometry::Matrix3 turn = geometry::toMatrix(*q_last_).transpose() * geometry::toMatrix(q_WB);
    out = Means{dv_B_ / dt_s_, geometry::logSO3(turn) / dt_s_};
  }
  q_last_ = q_WB;
  dv_B_.setZero();
  dt_s_ = 0.0;
  return out;
}

void ImuIntegrals::restart()
{
  q_last_.reset();
  dv_B_.setZero();
  dt_s_ = 0.0;
}

}  // namespace quad::plant
