// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/pose_history.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/distance.hpp"

namespace quad::mapping {
namespace {

using geometry::Pose3;
using geometry::Quaternion;
using geometry::Vector3;

constexpr std::int64_t kMs = 1'000'000;

Pose3 yawed(const Vector3& p, double yaw) { return {p, Quaternion{std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)}}; }

TEST(PoseHistory, BetweenTwoStatesThePoseIsInterpolated)
{
  PoseHistory h;
  ASSERT_TRUE(h.add(0, yawed(Vector3(0, 0, 1), 0.0), Vector3(1, 0, 0)));
  ASSERT_TRUE(h.add(4 * kMs, yawed(Vector3(0.004, 0, 1), 0.2), Vector3(1, 0, 0)));
  const auto mid = h.at(1 * kMs);
  ASSERT_TRUE(mid);
  EXPECT_NEAR(mid->p.x(), 0.001, 1e-12);
  EXPECT_NEAR(geometry::geodesicAngle(mid->q, yawed(Vector3::Zero(), 0.05).q), 0.0, 1e-9);
  // Exactly at a state: that state.
  EXPECT_NEAR(h.at(4 * kMs)->p.x(), 0.004, 1e-12);
}

TEST(PoseHistory, PastTheNewestOnlyALittleAndNotAcrossAGap)
{
  PoseHistoryConfig c;
  PoseHistory h(c);
  EXPECT_FALSE(h.at(0)) << "no state yet";
  ASSERT_TRUE(h.add(0, yawed(Vector3(0, 0, 1), 0.0), Vector3(2, 0, 0)));
  const auto ahead = h.at(5 * kMs);
  ASSERT_TRUE(ahead);
  EXPECT_NEAR(ahead->p.x(), 0.010, 1e-12) << "carried on at the newest velocity";
  EXPECT_FALSE(h.at(c.max_ahead_ns + 1));
  // A dropout longer than max_gap_ns: nothing within it.
  ASSERT_TRUE(h.add(c.max_gap_ns + 4 * kMs, yawed(Vector3(0.2, 0, 1), 0.0), Vector3(2, 0, 0)));
  EXPECT_FALSE(h.at(c.max_gap_ns / 2));
  EXPECT_FALSE(h.add(c.max_gap_ns + 4 * kMs, yawed(Vector3(0.2, 0, 1), 0.0), Vector3::Zero())) << "not newer";
}

TEST(PoseHistory, StatesOlderThanTheWindowAreForgotten)
{
  PoseHistoryConfig c;
  c.window_ns = 100 * kMs;
  PoseHistory h(c);
  for (std::int64_t t = 0; t <= 400 * kMs; t += 4 * kMs) {
    ASSERT_TRUE(h.add(t, yawed(Vector3::Zero(), 0.0), Vector3::Zero()));
  }
  EXPECT_FALSE(h.at(200 * kMs));
  EXPECT_TRUE(h.at(320 * kMs));
  EXPECT_EQ(h.newestNs(), 400 * kMs);
}

}  // namespace
}  // namespace quad::mapping
