// SPDX-License-Identifier: BSD-3-Clause
#include "quad/estimation/estimator_params.hpp"

#include "quad/common/layout.hpp"

namespace quad::estimation {

const common::ParamTable<EstimatorParams>& estimatorTable()
{
  using P = EstimatorParams;
  static const common::ParamTable<P> table = [] {
    common::ParamTable<P> t;
    t.number("imu.accel_noise", [](P& p) -> double& { return p.accel_noise; }, {1e-6, 10.0}, "m/s^2",
             "accelerometer white noise, per sample")
        .number("imu.gyro_noise", [](P& p) -> double& { return p.gyro_noise; }, {1e-7, 1.0}, "rad/s",
                "gyroscope white noise, per sample")
        .number("imu.accel_bias_walk", [](P& p) -> double& { return p.accel_bias_walk; }, {1e-9, 1.0}, "m/s^2/sqrt(s)",
                "accelerometer bias random walk")
        .number("imu.gyro_bias_walk", [](P& p) -> double& { return p.gyro_bias_walk; }, {1e-10, 0.1}, "rad/s/sqrt(s)",
                "gyroscope bias random walk")
        .number("imu.accel_bias_prior", [](P& p) -> double& { return p.accel_bias_prior; }, {1e-6, 10.0}, "m/s^2",
                "1-sigma of the accelerometer bias at start")
        .number("imu.gyro_bias_prior", [](P& p) -> double& { return p.gyro_bias_prior; }, {1e-7, 1.0}, "rad/s",
                "1-sigma of the gyroscope bias at start")
        .number("baro.drift", [](P& p) -> double& { return p.baro_drift; }, {1e-9, 10.0}, "m/sqrt(s)",
                "random walk of the barometer's offset")
        .number("baro.offset_prior", [](P& p) -> double& { return p.baro_offset_prior; }, {1e-4, 1000.0}, "m",
                "1-sigma of the offset once the first reading has set it")
        .vector("mag.field", [](P& p) -> Vector3& { return p.mag_field_W; }, {-100.0, 100.0}, "uT",
                "the local magnetic field, world frame (ENU)")
        .number("initial.velocity_std", [](P& p) -> double& { return p.initial_velocity_std; }, {1e-4, 100.0}, "m/s",
                "1-sigma of the velocity at an alignment at rest")
        .number("initial.tilt_std", [](P& p) -> double& { return p.initial_tilt_std; }, {1e-5, 1.0}, "rad",
                "1-sigma of roll and pitch at alignment")
        .number("initial.yaw_std", [](P& p) -> double& { return p.initial_yaw_std; }, {1e-5, 3.2}, "rad",
                "1-sigma of the yaw at alignment")
        .number("initial.rest_tolerance", [](P& p) -> double& { return p.rest_tolerance; }, {0.01, 9.0}, "m/s^2",
                "at rest the accelerometer reads gravity within this (below it by more: falling, aligned as moving)")
        .number("initial.rest_rate", [](P& p) -> double& { return p.rest_rate; }, {1e-3, 10.0}, "rad/s",
                "... and the gyroscope reads less than this")
        .number("initial.rest_speed", [](P& p) -> double& { return p.rest_speed; }, {0.01, 100.0}, "m/s",
                "... and the fixes, fitted with a line, move slower than this")
        .number("initial.rest_window", [](P& p) -> double& { return p.rest_window; }, {0.0, 10.0}, "s",
                "... all of it for this long: then aligned at rest, the tilt from the accelerometer")
        .number("initial.moving_after", [](P& p) -> double& { return p.moving_after; }, {0.0, 600.0}, "s",
                "no rest this long after the first fix: aligned as moving (level, the fixes' velocity)")
        .number("initial.moving_velocity_std", [](P& p) -> double& { return p.moving_velocity_std; }, {1e-3, 100.0},
                "m/s", "1-sigma of the velocity at an alignment not at rest")
        .number("initial.moving_tilt_std", [](P& p) -> double& { return p.moving_tilt_std; }, {1e-4, 1.5}, "rad",
                "1-sigma of roll and pitch at an alignment not at rest")
        .number("gate.probability", [](P& p) -> double& { return p.gate_probability; }, {0.5, 0.999999}, "",
                "an innovation beyond this chi-square quantile is an outlier, refused and counted")
        .number("position.max_age", [](P& p) -> double& { return p.max_fix_age; }, {0.0, 10.0}, "s",
                "fixes measured longer than this before the newest IMU sample are refused")
        .number("health.position_timeout", [](P& p) -> double& { return p.position_timeout; }, {0.01, 600.0}, "s",
                "without a fix taken for this long, the position is unaided")
        .number("health.heading_timeout", [](P& p) -> double& { return p.heading_timeout; }, {0.01, 600.0}, "s",
                "without a heading taken for this long, the heading is unaided")
        .number("health.imu_timeout", [](P& p) -> double& { return p.imu_timeout; }, {0.001, 10.0}, "s",
                "without an IMU sample for this long, the estimate is stale")
        .number("health.max_position_std", [](P& p) -> double& { return p.max_position_std; }, {0.001, 1000.0}, "m",
                "a larger position 1-sigma on any axis is unhealthy")
        .number("health.max_attitude_std", [](P& p) -> double& { return p.max_attitude_std; }, {1e-4, 3.2}, "rad",
                "a larger attitude 1-sigma about any axis is unhealthy");
    return t;
  }();
  return table;
}

common::ParamSchema estimatorSchema() { return estimatorTable().schema(); }

EstimatorParams estimatorParamsOf(const common::Params& params)
{
  EstimatorParams p = estimatorTable().read(params, common::configDir());
  if (p.mag_field_W.head<2>().norm() < 1.0) {
    throw common::ConfigError({common::configProblem(params.origin(), "mag.field", p.mag_field_W.head<2>().norm(),
                                                     "horizontal part in uT: below 1 uT the field gives no heading")});
  }
  return p;
}

}  // namespace quad::estimation
