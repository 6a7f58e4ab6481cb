// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The estimator's parameters (configs/estimation.yaml), declared once: what it assumes of
/// its sensors (noise, bias instability, the local magnetic field), its gates, and the
/// bounds its health is judged by.

#include "quad/common/param_table.hpp"
#include "quad/geometry/so3.hpp"

namespace quad::estimation {

using geometry::Vector3;

struct EstimatorParams {
  // The sensor models (what the filter assumes; a real IMU's datasheet, here the plant's).
  double accel_noise = 0.02;         ///< [m/s²] white, per IMU sample
  double gyro_noise = 0.002;         ///< [rad/s] white, per IMU sample
  double accel_bias_walk = 0.001;    ///< [m/s²/√s]
  double gyro_bias_walk = 0.0001;    ///< [rad/s/√s]
  double accel_bias_prior = 0.1;     ///< [m/s²] 1σ of the bias at start
  double gyro_bias_prior = 0.01;     ///< [rad/s]
  double baro_drift = 0.005;         ///< [m/√s] the barometer offset's random walk
  double baro_offset_prior = 0.5;    ///< [m] 1σ of the offset after the first reading sets it
  Vector3 mag_field_W{0.0, 21.0, -43.0};  ///< [µT] the local field, world frame (ENU)
  // Start.
  double initial_velocity_std = 0.5;  ///< [m/s]
  double initial_tilt_std = 0.02;     ///< [rad] roll and pitch, from the accelerometer at rest
  double initial_yaw_std = 0.05;      ///< [rad] from the magnetometer
  /// Alignment waits for the vehicle at rest, where the accelerometer reads gravity alone and
  /// gives the tilt: for rest_window every IMU sample reads gravity's magnitude within
  /// rest_tolerance [m/s²] and turns slower than rest_rate [rad/s], and the position fixes of
  /// that window, fitted with a line, move slower than rest_speed [m/s]. (A multirotor braking
  /// or cruising reads its thrust, along its own z, whatever its tilt.)
  double rest_tolerance = 1.0;
  double rest_rate = 0.1;
  double rest_speed = 0.2;
  double rest_window = 0.5;  ///< [s]
  /// Two cases align without rest, level with the wide 1σ below and the fixes' velocity: an
  /// accelerometer reading less than gravity by more than rest_tolerance (falling: a start in
  /// the air, nothing holds it up), and no rest moving_after [s] after the first fix.
  double moving_after = 3.0;
  double moving_velocity_std = 5.0;   ///< [m/s] 1σ of the velocity at an alignment not at rest
  double moving_tilt_std = 0.3;       ///< [rad] 1σ of roll and pitch at an alignment not at rest
  // Gates and health.
  double gate_probability = 0.999;   ///< an innovation beyond this χ² quantile is an outlier
  double max_fix_age = 0.5;          ///< [s] fixes stamped earlier than this behind the IMU are refused
  double position_timeout = 1.0;     ///< [s] without a fix taken, the position is unaided
  double heading_timeout = 1.0;      ///< [s] without a heading taken, the heading is unaided
  double imu_timeout = 0.05;         ///< [s] without an IMU sample, the estimate is stale
  double max_position_std = 0.5;     ///< [m] a larger position 1σ (any axis) is unhealthy
  double max_attitude_std = 0.1;     ///< [rad] a larger attitude 1σ (any axis) is unhealthy
  Vector3 gravity_W{0.0, 0.0, -9.81};  ///< [m/s²] not a key: the world's
};

/// configs/estimation.yaml: each key with its unit, range and the field it fills; the
/// defaults are EstimatorParams' own.
const common::ParamTable<EstimatorParams>& estimatorTable();
common::ParamSchema estimatorSchema();

/// The parameters as a file gives them; throws common::ConfigError naming the file and key
/// (a local field with no horizontal part gives no heading).
EstimatorParams estimatorParamsOf(const common::Params& params);

}  // namespace quad::estimation
