// SPDX-License-Identifier: BSD-3-Clause
// The camera gimbal: slew limits, range, and what the camera on it sees, in closed form.
#include "quad/plant/gimbal.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/so3.hpp"
#include "quad/plant/sensors.hpp"
#include "quad/plant/simulation.hpp"

namespace quad::plant {
namespace {

using world::Bounds;
using world::Obstacle;
using world::World;

using geometry::kPi;

GimbalConfig gimbal(double rate = 3.0)
{
  GimbalConfig c;
  c.enabled = true;
  c.slew_rate = rate;
  return c;
}

TEST(Gimbal, EachAxisSlewsAtItsRateAndStopsOnTheTarget)
{
  Gimbal g(gimbal(3.0), 0.0, 0.0);
  ASSERT_TRUE(g.aim(kPi / 2.0, -0.5));
  g.step(0.1);
  EXPECT_NEAR(g.yaw(), 0.3, 1e-12);
  EXPECT_NEAR(g.pitch(), -0.3, 1e-12);
  for (int i = 0; i < 20; ++i) {
    g.step(0.1);
  }
  EXPECT_NEAR(g.yaw(), kPi / 2.0, 1e-12);
  EXPECT_NEAR(g.pitch(), -0.5, 1e-12);
}

TEST(Gimbal, YawTurnsTheShortWayRoundAndPitchStaysInItsRange)
{
  Gimbal g(gimbal(1.0), 3.0, 0.0);
  g.aim(-3.0, 2.5);  // 0.28 rad away through ±π; pitch beyond straight up
  g.step(0.1);
  EXPECT_NEAR(geometry::wrapToPi(g.yaw() - 3.1), 0.0, 1e-12);
  for (int i = 0; i < 40; ++i) {
    g.step(0.1);
  }
  EXPECT_NEAR(g.yaw(), -3.0, 1e-12);
  EXPECT_NEAR(g.pitch(), kPi / 2.0, 1e-12);
}

TEST(Gimbal, ANonFiniteAimIsRefusedAndTheOldOneKept)
{
  Gimbal g(gimbal(), 0.0, 0.0);
  g.aim(1.0, 0.2);
  EXPECT_FALSE(g.aim(NAN, 0.0));
  EXPECT_FALSE(g.aim(0.0, INFINITY));
  for (int i = 0; i < 10; ++i) {
    g.step(0.1);
  }
  EXPECT_NEAR(g.yaw(), 1.0, 1e-12);
  EXPECT_NEAR(g.pitch(), 0.2, 1e-12);
}

World ceilingAndFloor(double ceiling)
{
  return World(Bounds{Vector3(-50, -50, 0), Vector3(50, 50, 50)}, Vector3::Zero(), Vector3(1, 0, 0),
               {Obstacle::makeBox({Vector3(0, 0, ceiling + 0.5), Vector3(100, 100, 1), 0.0})});
}

DepthCamera camera()
{
  DepthCameraConfig config;
  config.noise_std = 0.0;
  config.max_range = 30.0;
  return DepthCamera(config);
}

TEST(Gimbal, AimedStraightUpTheCameraSeesTheCeilingAsAPlaneAtItsHeight)
{
  // GIVEN a camera at 2 m, a ceiling at 7 m, the gimbal straight up (any yaw)
  Gimbal g(gimbal(), 0.7, kPi / 2.0);
  std::mt19937_64 rng(1);
  // WHEN it captures
  const DepthScan scan = camera().captureFrom(ceilingAndFloor(7.0), {Vector3(0, 0, 2), g.orientation_W()}, rng);
  // THEN every ray hits, at 5 m along the optical axis (the plane is perpendicular to it)
  EXPECT_EQ(scan.hits, 64 * 48);
  for (const auto& p : scan.points_S) {
    EXPECT_NEAR(p.x(), 5.0f, 1e-4f);
  }
}

TEST(Gimbal, AimedDownAtFortyFiveDegreesTheCentralRayMeetsTheGroundAtHRootTwo)
{
  // GIVEN a camera at 3 m, pitched 45° down, yawed 30° left
  Gimbal g(gimbal(), kPi / 6.0, -kPi / 4.0);
  std::mt19937_64 rng(1);
  const DepthScan scan = camera().captureFrom(ceilingAndFloor(40.0), {Vector3(0, 0, 3), g.orientation_W()}, rng);
  // THEN the ray through the image's centre (between the four middle pixels) travels 3√2 m,
  // and lands 3 m out along the yaw
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const int v : {23, 24}) {
    for (const int u : {31, 32}) {
      centre += scan.points_S[static_cast<std::size_t>(v * 64 + u)] / 4.0f;
    }
  }
  EXPECT_NEAR(centre.x(), 3.0 * std::sqrt(2.0), 0.01);  // along the optical axis
  const Vector3 hit_W = scan.sensor_W.transform(centre.cast<double>());
  EXPECT_NEAR(hit_W.z(), 0.0, 0.02);
  EXPECT_NEAR(hit_W.x(), 3.0 * std::cos(kPi / 6.0), 0.05);
  EXPECT_NEAR(hit_W.y(), 3.0 * std::sin(kPi / 6.0), 0.05);
}

TEST(Gimbal, TheCameraOnItKeepsItsPointingWhateverTheBodysAttitude)
{
  // GIVEN a plant whose camera hangs on the gimbal, aimed 0.4 rad up at yaw 1 rad
  SimulationConfig config;
  config.gimbal = gimbal(100.0);
  vehicle::VehicleParams v;
  v.mass = 2.0;
  v.radius = 0.35;
  Simulation sim(v, ceilingAndFloor(40.0), config);
  ASSERT_TRUE(sim.aimGimbal(1.0, 0.4));
  for (int i = 0; i < 20; ++i) {
    sim.step();  // 0.1 rad a step
  }
  // WHEN the body rolls and pitches
  RigidBodyState s = sim.state();
  s.p_W = Vector3(1, 2, 3);
  s.q_WB = geometry::fromAxisAngle(Vector3(1, 1, 0), 0.5);
  sim.setState(s);
  // THEN the camera sits at the mount point on the body and points where it was aimed
  const geometry::Pose3 camera_W = sim.cameraPose();
  EXPECT_TRUE(camera_W.p.isApprox(s.p_W + geometry::rotate(s.q_WB, config.depth.position_B)));
  const Vector3 axis = geometry::rotate(camera_W.q, Vector3::UnitX());
  EXPECT_NEAR(std::atan2(axis.y(), axis.x()), 1.0, 1e-9);
  EXPECT_NEAR(std::asin(axis.z()), 0.4, 1e-9);
  // and a plant without one refuses an aim
  Simulation fixed(v, ceilingAndFloor(40.0), SimulationConfig{});
  EXPECT_FALSE(fixed.aimGimbal(1.0, 0.4));
}

}  // namespace
}  // namespace quad::plant
