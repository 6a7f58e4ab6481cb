// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/depth_intake.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "quad/geometry/quaternion.hpp"

namespace quad::mapping {
namespace {

DepthFrame frame(float range)
{
  DepthFrame f;
  f.frame_id = "depth_front";
  f.points_S = {{range, 0.0F, 0.0F}, {range, 0.5F, -0.25F}};
  f.sensor_p_B = Vector3(0.1, 0.0, 0.0);  // 10 cm ahead of the body's origin, looking along x
  f.max_range = 20.0;
  return f;
}

TEST(DepthIntake, AFramesPointsArePlacedInTheWorldFromTheBodyAndTheMount)
{
  DepthIntake intake({"depth_front"});
  // The body at (1, 2, 3) facing +y (yawed a quarter turn): the sensor looks along +y.
  const geometry::Pose3 body{Vector3(1, 2, 3), geometry::fromAxisAngle(Vector3::UnitZ(), M_PI / 2)};
  const auto scan = intake.take(frame(2.0F), body, "");
  ASSERT_TRUE(std::holds_alternative<Scan>(scan)) << std::get<std::string>(scan);
  const Scan& s = std::get<Scan>(scan);
  EXPECT_NEAR((s.origin_W - Vector3(1, 2.1, 3)).norm(), 0.0, 1e-9);
  ASSERT_EQ(s.points_W.size(), 2u);
  EXPECT_NEAR((s.points_W[0] - Vector3(1, 4.1, 3)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((s.points_W[1] - Vector3(0.5, 4.1, 2.75)).norm(), 0.0, 1e-6);
  EXPECT_EQ(s.max_range, 20.0);
}

TEST(DepthIntake, AFrameItCannotPlaceIsRefusedSayingWhy)
{
  DepthIntake intake({"depth_front"});
  const geometry::Pose3 body;
  const auto refused = [&](const DepthFrame& f, const std::optional<geometry::Pose3>& pose) {
    const auto scan = intake.take(f, pose, "no state within 0.1 s of the cloud");
    return std::holds_alternative<std::string>(scan) ? std::get<std::string>(scan) : std::string();
  };
  DepthFrame f = frame(2.0F);
  f.frame_id = "lidar";
  EXPECT_EQ(refused(f, body), "unknown frame 'lidar'");
  f = frame(3.0F);
  f.sensor_q_BS = geometry::Quaternion{0.5, 0.0, 0.0, 0.0};
  EXPECT_EQ(refused(f, body), "sensor attitude is not a unit quaternion");
  f = frame(4.0F);
  f.sensor_p_B.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refused(f, body), "sensor position is not finite");
  EXPECT_EQ(refused(frame(5.0F), std::nullopt), "no state within 0.1 s of the cloud");
}

TEST(DepthIntake, TheFrameBeforeAgainIsAStuckCamerasWhateverBecameOfTheFirst)
{
  DepthIntake intake({"depth_front"});
  const geometry::Pose3 body;
  EXPECT_TRUE(std::holds_alternative<std::string>(intake.take(frame(2.0F), std::nullopt, "no pose yet")));
  const auto again = intake.take(frame(2.0F), body, "");
  ASSERT_TRUE(std::holds_alternative<std::string>(again));
  EXPECT_EQ(std::get<std::string>(again), "its points repeat the cloud before it's, bit for bit (a stuck camera)");
  EXPECT_TRUE(std::holds_alternative<Scan>(intake.take(frame(2.5F), body, "")));
}

}  // namespace
}  // namespace quad::mapping
