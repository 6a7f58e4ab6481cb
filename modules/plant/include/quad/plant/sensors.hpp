// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Simulated sensors: a forward-looking depth camera (ray casting against the world) and an
/// IMU (specific force and angular rate with white noise, and biases that start off by a
/// random turn-on offset and wander as random walks). Randomness comes from a generator the
/// caller owns, so a run is reproducible for a seed. The navigation aids (position, altitude,
/// heading) are in navigation_sensors.hpp.

#include <optional>
#include <random>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "quad/geometry/cspace.hpp"
#include "quad/world/world.hpp"

namespace quad::plant {

using geometry::Vector3;

struct DepthCameraConfig {
  int width = 64;                       ///< pixels
  int height = 48;                      ///< pixels
  double horizontal_fov = 1.5707963;    ///< [rad]
  double max_range = 20.0;              ///< [m]
  double noise_std = 0.01;              ///< [m] range noise, Gaussian
  double rate_hz = 10.0;                ///< [Hz]
  Vector3 position_B{0.1, 0.0, 0.0};    ///< [m] mount point, body frame
  double tilt_down = 0.0;               ///< [rad] pitch of the optical axis below body x
};

/// One depth frame: points in the sensor frame (x forward, y left, z up) and the sensor pose.
struct DepthScan {
  geometry::Pose3 sensor_W;                 ///< sensor pose in the world at capture
  std::vector<Eigen::Vector3f> points_S;    ///< every ray: hits, and misses beyond max range
  int hits = 0;
};

class DepthCamera {
public:
  /// A ray that hits nothing within max_range is reported as a point at kMissFactor ×
  /// max_range: beyond the range, so a mapper only clears space along it.
  static constexpr double kMissFactor = 1.25;

  /// Throws std::invalid_argument on a non-positive size, range or field of view.
  explicit DepthCamera(DepthCameraConfig config);

  const DepthCameraConfig& config() const { return config_; }
  /// Unit ray directions in the sensor frame, row by row from the top-left pixel.
  const std::vector<Vector3>& directions_S() const { return directions_; }
  /// Sensor pose for a body pose.
  geometry::Pose3 sensorPose(const geometry::Pose3& body_W) const;

  /// A frame from the camera on its fixed mount on a body at `body_W`.
  DepthScan capture(const world::World& world, const geometry::Pose3& body_W, std::mt19937_64& rng,
                    double extra_noise_std = 0.0) const;
  /// A frame from a camera at `sensor_W` (on a gimbal, say): rays cast from its origin, at the
  /// world and at `others` (other vehicles, each its bounding sphere).
  DepthScan captureFrom(const world::World& world, const geometry::Pose3& sensor_W, std::mt19937_64& rng,
                        double extra_noise_std = 0.0, std::span<const world::Sphere> others = {}) const;

private:
  DepthCameraConfig config_;
  geometry::Quaternion q_BS_;
  std::vector<Vector3> directions_;
};

struct ImuConfig {
  double accel_noise_std = 0.02;          ///< [m/s²] per sample
  double gyro_noise_std = 0.002;          ///< [rad/s] per sample
  Vector3 accel_bias = Vector3::Zero();   ///< [m/s²] the part of the bias every run has
  Vector3 gyro_bias = Vector3::Zero();    ///< [rad/s]
  double accel_turn_on_std = 0.05;        ///< [m/s²] per axis: the bias drawn at each start
  double gyro_turn_on_std = 0.005;        ///< [rad/s]
  double accel_bias_walk = 0.001;         ///< [m/s²/√s] the bias's random walk (instability)
  double gyro_bias_walk = 0.0001;         ///< [rad/s/√s]
  double rate_hz = 250.0;                 ///< [Hz]
};

/// The IMU's biases now.
struct ImuBias {
  Vector3 accel = Vector3::Zero();  ///< [m/s²] body frame
  Vector3 gyro = Vector3::Zero();   ///< [rad/s] body frame
};

/// Three independent standard normal draws, x first.
Vector3 standardNormal3(std::mt19937_64& rng);

/// The biases at turn-on: the configured ones plus a draw of the turn-on spread.
ImuBias turnOnBias(const ImuConfig& config, std::mt19937_64& rng);
/// Advances the biases' random walks by `dt_s`.
void walkBias(ImuBias& bias, const ImuConfig& config, double dt_s, std::mt19937_64& rng);

struct ImuSample {
  Vector3 specific_force_B;  ///< [m/s²] R_WBᵀ (a_W − g_W): +9.81 z at rest
  Vector3 angular_rate_B;    ///< [rad/s]
};

/// The ideal readings plus `bias` plus white noise (`extra_noise_std` adds to both channels'
/// standard deviation, in their units).
ImuSample measureImu(const ImuConfig& config, const ImuBias& bias, const geometry::Quaternion& q_WB, const Vector3& a_W,
                     const Vector3& w_B, const Vector3& gravity_W, std::mt19937_64& rng,
                     double extra_noise_std = 0.0);

/// The same from what the IMU integrated (ImuIntegrals): the specific force `force_B` [m/s²]
/// and the rate `w_B` [rad/s], both in the body frame, means over the sample period.
ImuSample measureImuIntegrals(const ImuConfig& config, const ImuBias& bias, const Vector3& force_B, const Vector3& w_B,
                              std::mt19937_64& rng, double extra_noise_std = 0.0);

/// What an IMU integrates between its samples, as real ones do at a rate above the one they
/// report: the specific force in the body frame, step by step (delta velocity), and the
/// rotation since the last sample (delta angle). A touchdown, which stops and levels the body
/// within a step, shows as the jolt and the turn it is; read at an instant, the rate would
/// miss the turn, and an estimator would keep the tilt it had.
class ImuIntegrals {
public:
  struct Means {
    Vector3 force_B;  ///< [m/s²] the mean specific force over the period, body frame
    Vector3 w_B;      ///< [rad/s] the rotation over the period, as a mean rate
  };
  /// One step of the dynamics: the velocity changed by `dv_W` over `dt_s`, the body at
  /// `R_WB_before` when it began (a stop comes before the turn it causes).
  void addStep(const geometry::Matrix3& R_WB_before, const Vector3& dv_W, const Vector3& gravity_W, double dt_s);
  /// A sample at attitude `q_WB`: the means since the last one (none before the first, nor
  /// after restart()), and the next period starts.
  std::optional<Means> sample(const geometry::Quaternion& q_WB);
  /// Forgets the period: a state set, not a motion felt.
  void restart();

private:
  Vector3 dv_B_ = Vector3::Zero();             ///< [m/s] Σ R_WBᵀ (Δv − g Δt)
  double dt_s_ = 0.0;                          ///< [s] the time those steps cover
  std::optional<geometry::Quaternion> q_last_;  ///< the attitude at the last sample
};

}  // namespace quad::plant
