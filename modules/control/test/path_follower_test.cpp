// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/path_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "closed_loop.hpp"

namespace quad::control {
namespace {

/// Distance from p to the polyline.
double toPolyline(const std::vector<Vector3>& w, const Vector3& p)
{
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < w.size(); ++i) {
    const Vector3 seg = w[i + 1] - w[i];
    const double u = std::clamp((p - w[i]).dot(seg) / seg.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (w[i] + u * seg - p).norm());
  }
  return best;
}

const std::vector<Vector3> kZigZag = {{0, 0, 2}, {6, 0, 2}, {6, 5, 2}, {12, 5, 3}, {12, -3, 3}, {20, -3, 2}};

TEST(PathFollower, CornersStayWithinTheirDeviationOfThePolyline)
{
  FollowerLimits limits;
  limits.corner_deviation = 0.1;
  const Trajectory t(kZigZag, limits);
  for (double s = 0.0; s <= t.length(); s += 0.01) {
    EXPECT_LE(toPolyline(kZigZag, t.at(s).p), 0.1 + 1e-6) << "s = " << s;
  }
  EXPECT_GT(t.length(), 0.0);
}

TEST(PathFollower, TimeLawRespectsSpeedAccelerationAndJerkAndEndsAtRest)
{
  FollowerLimits limits;
  PathFollower f(limits);
  f.hold(kZigZag.front(), 0.0);
  ASSERT_TRUE(f.setPath(kZigZag, 1));
  const double dt = 0.004;
  double t = 0.0;
  double last_a = 0.0;
  double last_speed = 0.0;
  double worst_jerk = 0.0, worst_acc = 0.0, worst_speed = 0.0;
  while (!f.finished() && t < 120.0) {
    const Reference r = f.step(dt);
    const double speed = r.v_W.norm();
    if (f.finished()) {
      EXPECT_LE(last_speed, 0.05);  // the stop on the end point, from at most 5 cm/s
      break;
    }
    const double along = (speed - last_speed) / dt;  // tangential acceleration
    worst_speed = std::max(worst_speed, speed);
    worst_acc = std::max(worst_acc, std::abs(along));
    worst_jerk = std::max(worst_jerk, std::abs(along - last_a) / dt);
    last_a = along;
    last_speed = speed;
    t += dt;
  }
  EXPECT_TRUE(f.finished());
  EXPECT_LT(t, 60.0);
  EXPECT_LE(worst_speed, limits.max_speed + 1e-9);
  EXPECT_LE(worst_acc, limits.max_acceleration + 1e-6);
  EXPECT_LE(worst_jerk, limits.max_jerk + 1e-3);
  EXPECT_LT((f.reference().p_W - kZigZag.back()).norm(), 1e-6);
  EXPECT_EQ(f.reference().v_W.norm(), 0.0);
}

TEST(PathFollower, ANewPathIsJoinedWithoutAJump)
{
  PathFollower f({});
  f.hold(Vector3(0, 0, 2), 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {20, 0, 2}}, 1));
  for (int k = 0; k < 1000; ++k) {
    f.step(0.004);
  }
  const Reference before = f.reference();
  ASSERT_GT(before.v_W.norm(), 1.0);
  // A replanned path that bends away.
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {before.p_W.x() + 1.0, 0, 2}, {before.p_W.x() + 3, 4, 2}, {20, 4, 2}}, 2));
  const Reference after = f.step(0.004);
  EXPECT_LT((after.p_W - before.p_W).norm(), before.v_W.norm() * 0.004 + 1e-3);
  EXPECT_NEAR(after.v_W.norm(), before.v_W.norm(), 0.05);
  EXPECT_EQ(f.version(), 2U);
}

TEST(PathFollower, ReplansFasterThanTheLeadInDoNotCarryTheReferenceOn)
{
  // GIVEN a reference slowing to 0.35 m/s along +x
  PathFollower f({});
  f.hold(Vector3(0, 0, 2), 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {2, 0, 2}}, 1));
  while (f.reference().p_W.x() < 1.85) {
    f.step(0.004);
  }
  const Reference start = f.reference();
  ASSERT_GT(start.v_W.x(), 0.2);
  // WHEN every 0.2 s a new path leads back and away (an obstacle ahead), as a planner
  // replanning from inside an inflated margin sends them
  double furthest = start.p_W.x();
  for (std::uint32_t version = 2; version < 12; ++version) {
    const double x = f.reference().p_W.x();
    ASSERT_TRUE(f.setPath({{x, 0, 2}, {x - 0.5, 0.5, 2}, {x - 0.5, 3, 2}}, version));
    for (int k = 0; k < 50; ++k) {
      furthest = std::max(furthest, f.step(0.004).p_W.x());
    }
  }
  // THEN the reference goes no further than its first lead-in (0.5 s of its speed), and
  // turns back (it crept on for as long as the paths came when each brought a lead-in anew)
  EXPECT_LT(furthest - start.p_W.x(), 0.5 * start.v_W.norm() + 0.02);
  EXPECT_LT(f.reference().p_W.x(), furthest - 0.1);
}

TEST(PathFollower, APathTurningBackJustAheadIsJoinedWithinTheBrakingAndLateralLimits)
{
  // GIVEN a reference at ~1 m/s along +x whose replans (every 0.2 s) go on ahead and bend
  // later, so its lead-in is kept and comes ever nearer
  FollowerLimits limits;
  PathFollower f(limits);
  f.hold(Vector3(0, 0, 2), 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {1.5, 0, 2}, {3, 2, 2}}, 1));
  std::uint32_t version = 1;
  while (f.reference().p_W.x() < 1.0) {
    f.step(0.004);
  }
  double worst = 0.0;  // the fastest change of the reference velocity [m/s²]
  Vector3 last_v = f.reference().v_W;
  const auto fly = [&](int steps) {
    for (int k = 0; k < steps; ++k) {
      const Reference r = f.step(0.004);
      worst = std::max(worst, (r.v_W - last_v).norm() / 0.004);
      last_v = r.v_W;
    }
  };
  for (int i = 0; i < 3; ++i) {
    const Vector3 p = f.reference().p_W;
    ASSERT_TRUE(f.setPath({p, {p.x() + 1.5, p.y(), 2}, {p.x() + 3, p.y() + 2, 2}}, ++version));
    fly(50);
  }
  // WHEN the next path turns back (an obstacle seen ahead)
  const Reference before = f.reference();
  ASSERT_GT(before.v_W.norm(), 0.5);
  ASSERT_TRUE(f.setPath({before.p_W, {before.p_W.x() - 1.0, before.p_W.y() + 1.0, 2},
                         {before.p_W.x() - 1.0, before.p_W.y() + 4.0, 2}}, ++version));
  double furthest = before.p_W.x();
  for (int k = 0; k < 1000; ++k) {
    fly(1);
    furthest = std::max(furthest, f.reference().p_W.x());
  }
  // THEN the reference brakes before it turns: its velocity never changes faster than the
  // position loop's own horizontal acceleration limit (it swung round at 170 m/s² when the
  // turn came 2 cm ahead at full speed), and it goes on no further than that braking
  // takes, with the lead-in
  EXPECT_LT(worst, GeometricGains{}.max_acceleration);
  EXPECT_LT(furthest - before.p_W.x(), 0.5 * before.v_W.norm() + 0.05);
  EXPECT_LT(f.reference().p_W.x(), before.p_W.x() - 0.5);
}

TEST(PathFollower, YawFacesAlongThePathAtALimitedRate)
{
  FollowerLimits limits;
  limits.max_yaw_rate = 0.5;
  PathFollower f(limits);
  f.hold(Vector3(0, 0, 2), 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {0, 10, 2}}, 1));  // straight along +y: yaw π/2
  double last = 0.0;
  for (int k = 0; k < 2500; ++k) {
    const Reference r = f.step(0.004);
    EXPECT_LE(std::abs(geometry::wrapToPi(r.yaw - last)), 0.5 * 0.004 + 1e-12);
    last = r.yaw;
  }
  EXPECT_NEAR(last, geometry::kPi / 2.0, 1e-3);
}

TEST(PathFollower, BadPathsAreRefusedAndTheOldOneKept)
{
  PathFollower f({});
  f.hold(Vector3(1, 2, 3), 0.0);
  EXPECT_FALSE(f.setPath({}, 1));
  EXPECT_FALSE(f.setPath({{0, 0, 0}, {NAN, 0, 0}}, 2));
  EXPECT_FALSE(f.version().has_value());
  EXPECT_TRUE(f.setPath({{1, 2, 3}}, 3));  // a single waypoint: hold there
  f.step(0.004);
  EXPECT_TRUE(f.finished());
}

TEST(PathFollower, SharpCornersAreFlownInsideTheMargin)
{
  // GIVEN a path with right-angle and acute corners, and a 0.25 m margin kept free around it
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  FollowerLimits limits;
  limits.corner_deviation = 0.1;
  PathFollower f(limits);
  f.hold(kZigZag.front(), 0.0);
  ASSERT_TRUE(f.setPath(kZigZag, 1));
  plant::RigidBodyState s;
  s.p_W = kZigZag.front();
  s.rotor_speed.fill(v.hoverRotorSpeed());
  // WHEN the controller flies the follower's reference on the plant
  const auto trace = test::fly(v, test::scaledGains(v), s, 40.0, [&](double) { return f.step(0.004); });
  // THEN the vehicle never leaves the margin, and arrives
  double worst = 0.0;
  for (const auto& sample : trace) {
    worst = std::max(worst, toPolyline(kZigZag, sample.state.p_W));
  }
  EXPECT_LE(worst, 0.25) << "largest distance from the path " << worst;
  EXPECT_LT((trace.back().state.p_W - kZigZag.back()).norm(), 0.05);
}

}  // namespace
}  // namespace quad::control
