// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/quaternion.hpp"

namespace quad::plant {
namespace {

using world::Bounds;
using world::Obstacle;
using world::World;

World wallAt(double x)
{
  return World(Bounds{Vector3(-20, -50, 0), Vector3(50, 50, 50)}, Vector3::Zero(), Vector3(1, 0, 0),
               {Obstacle::makeBox({Vector3(x + 0.5, 0, 25), Vector3(1, 100, 50), 0.0})});
}

TEST(DepthCamera, AWallAheadIsAPlaneAtItsDistance)
{
  DepthCameraConfig config;
  config.noise_std = 0.0;
  config.position_B = Vector3::Zero();
  const DepthCamera camera(config);
  std::mt19937_64 rng(1);
  const DepthScan scan = camera.capture(wallAt(8.0), {Vector3(0, 0, 10), {}}, rng);
  ASSERT_EQ(scan.points_S.size(), 64U * 48U);
  EXPECT_EQ(scan.hits, 64 * 48);
  for (const auto& p : scan.points_S) {
    EXPECT_NEAR(p.x(), 8.0f, 1e-5f);  // every point of the plane x = 8
  }
}

TEST(DepthCamera, MissesLieBeyondTheRangeAndTiltSeesTheGround)
{
  DepthCameraConfig config;
  config.noise_std = 0.0;
  config.max_range = 10.0;
  const DepthCamera camera(config);
  std::mt19937_64 rng(1);
  const DepthScan open = camera.capture(wallAt(40.0), {Vector3(0, 0, 25), {}}, rng);
  EXPECT_EQ(open.hits, 0);
  for (const auto& p : open.points_S) {
    EXPECT_NEAR(p.norm(), 12.5f, 1e-4f);
  }
  config.tilt_down = geometry::kPi / 2.0;  // looking straight down from 3 m
  const DepthCamera down(config);
  const DepthScan ground = down.capture(wallAt(40.0), {Vector3(0, 0, 3), {}}, rng);
  EXPECT_EQ(ground.hits, 64 * 48);
  const auto centre = ground.points_S[static_cast<std::size_t>(24 * 64 + 32)];
  EXPECT_NEAR(centre.norm(), 3.0f, 0.1f);
}

TEST(DepthCamera, RangeNoiseHasTheConfiguredSpread)
{
  DepthCameraConfig config;
  config.noise_std = 0.05;
  config.position_B = Vector3::Zero();
  const DepthCamera camera(config);
  std::mt19937_64 rng(3);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20; ++k) {
    for (const auto& p : camera.capture(wallAt(8.0), {Vector3(0, 0, 10), {}}, rng).points_S) {
      const double e = static_cast<double>(p.x()) - 8.0;
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  EXPECT_NEAR(sum / n, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.05 * 0.9, 0.01);  // range noise projected on x (cos of ray angles)
}

TEST(Imu, AtRestItReadsGravityUpPlusBias)
{
  ImuConfig config;
  ImuBias bias;
  bias.accel = {0.1, -0.2, 0.05};
  bias.gyro = {0.01, 0.0, -0.02};
  std::mt19937_64 rng(9);
  Vector3 f_sum = Vector3::Zero();
  Vector3 w_sum = Vector3::Zero();
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const ImuSample s = measureImu(config, bias, {}, Vector3::Zero(), Vector3::Zero(), Vector3(0, 0, -9.81), rng);
    f_sum += s.specific_force_B;
    w_sum += s.angular_rate_B;
  }
  EXPECT_LT((f_sum / n - Vector3(0.1, -0.2, 9.86)).norm(), 1e-3);
  EXPECT_LT((w_sum / n - Vector3(0.01, 0.0, -0.02)).norm(), 1e-4);
  // In free fall the accelerometer reads zero (besides bias and noise).
  config = ImuConfig{};
  config.accel_noise_std = 0.0;
  const ImuSample falling = measureImu(config, {}, {}, Vector3(0, 0, -9.81), Vector3::Zero(), Vector3(0, 0, -9.81), rng);
  EXPECT_LT(falling.specific_force_B.norm(), 1e-12);
}

// GIVEN a body turning at a steady rate about a tilted axis while it accelerates steadily,
// stepped at 1 ms WHEN the IMU samples every 4 ms THEN the first sample has nothing to report,
// and each one after reads the turn's rate exactly and the specific force the steps felt in
// their own body frames (so the mean of R_WBᵀ (a − g) over the period).
TEST(Imu, IntegralsReadTheRotationAndTheForceFeltOverThePeriod)
{
  ImuIntegrals imu;
  const Vector3 w_B(0.3, -1.2, 2.0);
  const Vector3 a_W(1.0, -2.0, 0.5);
  const Vector3 g_W(0, 0, -9.81);
  const double dt = 0.001;
  geometry::Quaternion q = geometry::fromAxisAngle(Vector3(1, 1, 0), 0.4);
  EXPECT_FALSE(imu.sample(q).has_value());
  Vector3 expected_sum = Vector3::Zero();
  for (int k = 1; k <= 4; ++k) {
    const geometry::Matrix3 R = geometry::toMatrix(q);
    imu.addStep(R, a_W * dt, g_W, dt);
    expected_sum += R.transpose() * (a_W - g_W);
    q = q * geometry::fromAxisAngle(w_B, w_B.norm() * dt);
  }
  const auto means = imu.sample(q);
  ASSERT_TRUE(means.has_value());
  EXPECT_LT((means->w_B - w_B).norm(), 1e-9);
  EXPECT_LT((means->force_B - expected_sum / 4.0).norm(), 1e-12);
  // restarted (a state set), it again has nothing to report at its next sample
  imu.addStep(geometry::toMatrix(q), a_W * dt, g_W, dt);
  imu.restart();
  EXPECT_FALSE(imu.sample(q).has_value());
}

// GIVEN many IMUs turned on WHEN their biases are drawn and walk for T THEN the turn-on
// biases spread by their std dev around the configured part, and the walks' spread grows
// as walk × √T (a random walk's variance is linear in time).
TEST(Imu, TurnOnBiasesSpreadAsConfiguredAndTheirWalksGrowAsTheRootOfTime)
{
  ImuConfig config;
  config.accel_bias = {0.2, 0.0, 0.0};
  std::mt19937_64 rng(5);
  const int n = 1000;
  const double t = 100.0;
  const double dt = 0.1;
  double accel_x = 0.0;
  double accel_x2 = 0.0;
  double walked2 = 0.0;
  double gyro_walked2 = 0.0;
  for (int k = 0; k < n; ++k) {
    ImuBias b = turnOnBias(config, rng);
    accel_x += b.accel.x();
    accel_x2 += (b.accel.x() - 0.2) * (b.accel.x() - 0.2);
    const ImuBias start = b;
    for (double s = 0.0; s < t - 1e-9; s += dt) {
      walkBias(b, config, dt, rng);
    }
    walked2 += (b.accel - start.accel).squaredNorm() / 3.0;
    gyro_walked2 += (b.gyro - start.gyro).squaredNorm() / 3.0;
  }
  EXPECT_NEAR(accel_x / n, 0.2, 0.006);
  EXPECT_NEAR(std::sqrt(accel_x2 / n), config.accel_turn_on_std, 0.004);
  EXPECT_NEAR(std::sqrt(walked2 / n), config.accel_bias_walk * std::sqrt(t), 0.05 * config.accel_bias_walk * std::sqrt(t));
  EXPECT_NEAR(std::sqrt(gyro_walked2 / n), config.gyro_bias_walk * std::sqrt(t), 0.05 * config.gyro_bias_walk * std::sqrt(t));
}

}  // namespace
}  // namespace quad::plant
