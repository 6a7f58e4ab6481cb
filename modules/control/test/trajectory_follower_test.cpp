// SPDX-License-Identifier: BSD-3-Clause
// The trajectory follower: limits kept and rest at the end, replans taken without a jump or
// refused with the backup flown on, braking along the trajectory, heading, and the closed loop
// inside the path's margin.
#include "quad/control/trajectory_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "closed_loop.hpp"
#include "quad/geometry/polyline.hpp"

namespace quad::control {
namespace {

const std::vector<Vector3> kZigZag = {{0, 0, 2}, {6, 0, 2}, {6, 5, 2}, {12, 5, 3}, {12, -3, 3}, {20, -3, 2}};
constexpr double kTick = 0.004;  // [s] the control rate's period

TrajectoryFollower follower(const FollowerLimits& limits)
{
  return TrajectoryFollower(limits, generatorConfig(limits, test::loadVehicle("x500"), GeometricGains{}.max_tilt));
}

FollowerLimits fast()
{
  FollowerLimits l;
  l.max_speed = 8.0;
  l.max_acceleration = 5.0;
  l.max_jerk = 25.0;
  return l;
}

TEST(TrajectoryFollower, FliesAPathWithinItsLimitsAndComesToRestOnItsEnd)
{
  // GIVEN a zig-zag path in 3D, at a walking and at a fast pace
  for (const FollowerLimits& limits : {FollowerLimits{}, fast()}) {
    TrajectoryFollower f = follower(limits);
    f.hold(kZigZag.front(), 0.0, 0.0);
    ASSERT_TRUE(f.setPath(kZigZag, 1, 0.0)) << f.lastRefusal();
    // WHEN its reference is sampled each tick to the end
    double t = 0.0;
    double worst_speed = 0.0, worst_acc = 0.0, worst_jerk = 0.0, worst_off = 0.0;
    while (!f.finished(t) && t < 120.0) {
      const Reference r = f.step(t);
      worst_speed = std::max(worst_speed, r.v_W.norm());
      worst_acc = std::max(worst_acc, r.a_W.norm());
      worst_jerk = std::max(worst_jerk, r.j_W.norm());
      worst_off = std::max(worst_off, geometry::distanceToPolyline(kZigZag, r.p_W));
      t += kTick;
    }
    // THEN it keeps the speed, acceleration and jerk limits and the corridor, and rests on the end
    EXPECT_TRUE(f.finished(t));
    EXPECT_LE(worst_speed, limits.max_speed * 1.01);
    EXPECT_LE(worst_acc, limits.max_acceleration * 1.01);
    EXPECT_LE(worst_jerk, limits.max_jerk * 1.01);
    EXPECT_LE(worst_off, limits.corridor * 1.01);
    const Reference end = f.step(t);
    EXPECT_LT((end.p_W - kZigZag.back()).norm(), 1e-6);
    EXPECT_EQ(end.v_W.norm(), 0.0);
    EXPECT_EQ(f.version(), 1U);
  }
}

TEST(TrajectoryFollower, AReplanIsTakenFromTheReferenceWithoutAJump)
{
  // GIVEN a reference cruising along +x
  TrajectoryFollower f = follower(fast());
  f.hold(Vector3(0, 0, 2), 0.0, 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {40, 0, 2}}, 1, 0.0));
  double t = 0.0;
  for (; t < 2.0; t += kTick) {
    f.step(t);
  }
  const Reference before = f.step(t);
  ASSERT_GT(before.v_W.norm(), 3.0);
  // WHEN a replan bends away ahead (from where the planner expected the vehicle, near it)
  const Vector3 p = before.p_W;
  ASSERT_TRUE(f.setPath({p + Vector3(0.1, 0.05, 0), p + Vector3(6, 0, 0), p + Vector3(12, 4, 0), p + Vector3(25, 4, 0)},
                        2, t))
      << f.lastRefusal();
  // THEN the reference and its feed-forward go on as they were
  const Reference after = f.step(t);
  EXPECT_LT((after.p_W - before.p_W).norm(), 1e-9);
  EXPECT_LT((after.v_W - before.v_W).norm(), 1e-6);
  EXPECT_LT((after.a_W - before.a_W).norm(), 1e-5);
  EXPECT_LT((after.j_W - before.j_W).norm(), 1e-3);
  EXPECT_EQ(f.version(), 2U);
  EXPECT_EQ(f.taken(), 3U);  // the hold, the first path, the replan
}

TEST(TrajectoryFollower, AHoverNearAPathsStartGoesStraightOnRatherThanDippingToIt)
{
  // GIVEN a reference at rest 0.15 m above the start of a level path (planned during the climb)
  FollowerLimits limits = fast();
  limits.corridor = 0.2;
  TrajectoryFollower f = follower(limits);
  const Vector3 hover(0, 0, 2);
  f.hold(hover, 0.0, 0.0);
  const std::vector<Vector3> path{{0, 0, 1.85}, {20, 0, 1.85}};
  // WHEN it takes the path
  ASSERT_TRUE(f.setPath(path, 1, 0.0)) << f.lastRefusal();
  // THEN it heads for the path's end at once: it never sinks faster than the straight line from
  // the hover to that end, keeps within the corridor of that line, and rests on the end
  const std::vector<Vector3> hop{hover, path.back()};
  double t = 0.0;
  double sinking = 0.0, off = 0.0;
  for (; !f.finished(t) && t < 60.0; t += kTick) {
    const Reference r = f.step(t);
    sinking = std::max(sinking, -r.v_W.z() - 0.15 / 20.0 * std::max(0.0, r.v_W.x()));
    off = std::max(off, geometry::distanceToPolyline(hop, r.p_W));
  }
  EXPECT_LT(sinking, 0.05);
  EXPECT_LE(off, limits.corridor * 1.01);
  EXPECT_LT((f.step(t).p_W - path.back()).norm(), 1e-6);
}

TEST(TrajectoryFollower, APathNoTrajectoryGoesStraightOnToIsJoinedAtItsNearestPointInstead)
{
  // GIVEN the demo's limits, and a reference just setting off (0.12 s into a path that leads
  // away), a new path passing within the corridor of it and turning back up and away
  FollowerLimits limits;
  limits.max_speed = 5.0;
  limits.max_acceleration = 4.0;
  limits.max_jerk = 25.0;
  TrajectoryFollower f = follower(limits);
  f.hold(Vector3(0, 0, 2), 0.0, 0.0);
  ASSERT_TRUE(f.setPath({Vector3(0, 0, 2), Vector3(0.6, -3.6, 2.1)}, 1, 0.0)) << f.lastRefusal();
  const double t1 = 0.12;
  Reference r;
  for (double t = 0.0; t <= t1; t += kTick) {
    r = f.step(t);
  }
  const Vector3 far = r.p_W + Vector3(-9.7, 3.2, 1.16);
  const std::vector<Vector3> path{r.p_W + Vector3(-0.02, -0.025, 0.0), far, far + Vector3(5, 0, 0)};
  // WHEN it is given (no trajectory within the limits heads straight for its second waypoint:
  // the minimum-snap piece over the whole hop from a reference still accelerating away)
  // THEN it is taken, joined at the point nearest the reference, and flown within the limits to
  // rest on its end
  ASSERT_TRUE(f.setPath(path, 2, t1)) << f.lastRefusal();
  double t = t1;
  double worst_speed = 0.0, worst_acc = 0.0;
  for (; !f.finished(t) && t < 60.0; t += kTick) {
    const Reference s = f.step(t);
    worst_speed = std::max(worst_speed, s.v_W.norm());
    worst_acc = std::max(worst_acc, s.a_W.norm());
  }
  EXPECT_LE(worst_speed, limits.max_speed * 1.01);
  EXPECT_LE(worst_acc, limits.max_acceleration * 1.01);
  EXPECT_LT((f.step(t).p_W - path.back()).norm(), 1e-6);
}

TEST(TrajectoryFollower, APathTooShortToStopOnIsRefusedAndTheTrajectoryFlownStopsWhereItWasMadeTo)
{
  // GIVEN a fast reference whose trajectory ends at rest 30 m on
  TrajectoryFollower f = follower(fast());
  f.hold(Vector3(0, 0, 2), 0.0, 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {30, 0, 2}}, 1, 0.0));
  double t = 0.0;
  for (; f.reference().v_W.norm() < 6.0; t += kTick) {
    f.step(t);
  }
  const Vector3 p = f.reference().p_W;
  // WHEN a replan's known-free part ends a metre ahead (braking needs several)
  EXPECT_FALSE(f.setPath({p, p + Vector3(1, 0, 0)}, 2, t));
  EXPECT_FALSE(f.lastRefusal().empty());
  EXPECT_EQ(f.refused(), 1U);
  // THEN the trajectory flown goes on, the backup: to rest at its own end, never past it
  double furthest = 0.0;
  for (; !f.finished(t); t += kTick) {
    furthest = std::max(furthest, f.step(t).p_W.x());
  }
  EXPECT_EQ(f.version(), 1U);
  EXPECT_LE(furthest, 30.0 + 1e-6);
  EXPECT_EQ(f.step(t).v_W.norm(), 0.0);
}

TEST(TrajectoryFollower, BrakingStopsAlongTheTrajectorySoonerThanItsEnd)
{
  TrajectoryFollower f = follower(fast());
  const std::vector<Vector3> path{{0, 0, 2}, {20, 0, 2}, {30, 8, 2}, {50, 8, 2}};
  f.hold(path.front(), 0.0, 0.0);
  ASSERT_TRUE(f.setPath(path, 1, 0.0));
  double t = 0.0;
  for (; f.reference().v_W.norm() < 7.0; t += kTick) {
    f.step(t);
  }
  const Reference before = f.step(t);
  const double end_before = f.trajectory().endTime();
  f.brake(t);
  // The reference goes on without a jump and comes to rest within the limits, on the path's
  // corridor, before the trajectory it braked would have.
  const Reference first = f.step(t);
  EXPECT_LT((first.v_W - before.v_W).norm() + (first.a_W - before.a_W).norm(), 1e-6);
  double worst_acc = 0.0;
  for (; !f.finished(t); t += kTick) {
    const Reference r = f.step(t);
    worst_acc = std::max(worst_acc, r.a_W.norm());
    EXPECT_LE(geometry::distanceToPolyline(path, r.p_W), fast().corridor * 1.01);
  }
  EXPECT_LE(worst_acc, fast().max_acceleration * 1.01);
  EXPECT_LT(t, end_before);
  EXPECT_FALSE(f.version().has_value());
}

TEST(TrajectoryFollower, HeadingFacesAlongTheMotionAtALimitedRate)
{
  FollowerLimits limits;
  limits.max_yaw_rate = 0.5;
  TrajectoryFollower f = follower(limits);
  f.hold(Vector3(0, 0, 2), 0.0, 0.0);
  ASSERT_TRUE(f.setPath({{0, 0, 2}, {0, 10, 2}}, 1, 0.0));  // straight along +y: yaw π/2
  double last = 0.0;
  double t = 0.0;
  for (; t < 10.0; t += kTick) {
    const Reference r = f.step(t);
    EXPECT_LE(std::abs(geometry::wrapToPi(r.yaw - last)), 0.5 * kTick + 1e-9);
    last = r.yaw;
  }
  EXPECT_NEAR(last, geometry::kPi / 2.0, 1e-3);
}

TEST(TrajectoryFollower, BadPathsAreRefusedAndTheTrajectoryKept)
{
  TrajectoryFollower f = follower({});
  f.hold(Vector3(1, 2, 3), 0.0, 0.0);
  EXPECT_FALSE(f.setPath({}, 1, 0.0));
  EXPECT_FALSE(f.setPath({{0, 0, 0}, {NAN, 0, 0}}, 2, 0.0));
  EXPECT_FALSE(f.version().has_value());
  EXPECT_EQ(f.refused(), 2U);
  EXPECT_TRUE(f.setPath({{1, 2, 3}}, 3, 0.0));  // a single waypoint where it is: holds there
  EXPECT_TRUE(f.finished(f.trajectory().endTime()));
  EXPECT_EQ(f.step(5.0).p_W, Vector3(1, 2, 3));
}

TEST(TrajectoryFollower, TheClosedLoopFliesSharpCornersInsideTheMargin)
{
  // GIVEN a path with right-angle corners, and a 0.25 m margin kept free around it
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  for (const FollowerLimits& limits : {FollowerLimits{}, fast()}) {
    TrajectoryFollower f = follower(limits);
    f.hold(kZigZag.front(), 0.0, 0.0);
    ASSERT_TRUE(f.setPath(kZigZag, 1, 0.0));
    plant::RigidBodyState s;
    s.p_W = kZigZag.front();
    s.rotor_speed.fill(v.hoverRotorSpeed());
    // WHEN the controller flies the follower's reference on the plant
    const auto trace = test::fly(v, test::scaledGains(v), s, f.trajectory().endTime() + 2.0,
                                 [&](double t) { return f.step(t); });
    // THEN the vehicle never leaves the margin, and arrives
    double worst = 0.0;
    for (const auto& sample : trace) {
      worst = std::max(worst, geometry::distanceToPolyline(kZigZag, sample.state.p_W));
    }
    EXPECT_LE(worst, 0.25) << "largest distance from the path " << worst << " at " << limits.max_speed << " m/s";
    EXPECT_LT((trace.back().state.p_W - kZigZag.back()).norm(), 0.05);
  }
}

}  // namespace
}  // namespace quad::control
