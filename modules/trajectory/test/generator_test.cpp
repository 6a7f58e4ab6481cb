// SPDX-License-Identifier: BSD-3-Clause
// The generator: limits and corridor kept on random paths, continuity where a new trajectory
// starts from one flown, its pace against the time-optimal bound, stops, refused input.
#include "quad/trajectory/generator.hpp"

#include <gtest/gtest.h>

#include <random>

#include "quad/geometry/polyline.hpp"

namespace quad::trajectory {
namespace {

GeneratorConfig fastConfig()
{
  GeneratorConfig c;
  c.limits.max_speed = 10.0;
  c.limits.max_acceleration = 6.0;
  c.limits.max_jerk = 30.0;
  c.limits.max_tilt = 0.6;
  c.limits.max_thrust = 16.0;
  c.limits.min_thrust = 4.0;
  c.corridor = 0.25;
  c.corner_deviation = 0.15;
  return c;
}

/// The control's braking generator for the x500 at its shipped 2 m/s: 4 m/s² and 40 m/s³.
GeneratorConfig brakingConfig()
{
  GeneratorConfig c = fastConfig();
  c.limits.max_speed = 2.0;
  c.limits.max_acceleration = 4.0;
  c.limits.max_jerk = 40.0;
  c.limits.max_tilt = 0.48;
  c.limits.max_thrust = 13.7;
  c.limits.min_thrust = 3.27;
  c.corridor = 0.1;
  c.corner_deviation = 0.08;
  return c;
}

/// The largest distance [m] of the trajectory from `free`, densely sampled.
double largestDeviation(const Trajectory& t, const std::vector<std::vector<Vector3>>& free)
{
  double worst = 0.0;
  for (const Piece& piece : t.pieces()) {
    for (int k = 0; k <= 40; ++k) {
      const Vector3 p = piece.at(piece.duration * k / 40).p;
      double best = 1e9;
      for (const auto& polyline : free) {
        best = std::min(best, geometry::distanceToPolyline(polyline, p));
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

/// The limits kept on every piece; the first within `transition` (the factor on durations the
/// generator allows a moving start's turn onto the path: speed by it, acceleration by its
/// square, jerk by its cube).
void expectWithin(const Trajectory& t, const GeneratorConfig& c, double transition = 1.0)
{
  const Limits& l = c.limits;
  for (std::size_t i = 0; i < t.pieces().size(); ++i) {
    const double f = i == 0 ? transition : 1.0;
    const Extremes e = extremes(Trajectory(0.0, {t.pieces()[i]}), l.gravity, 64);
    EXPECT_LE(e.speed, l.max_speed * f * 1.01) << "piece " << i;
    EXPECT_LE(e.acceleration, l.max_acceleration * f * f * 1.01) << "piece " << i;
    EXPECT_LE(e.jerk, l.max_jerk * f * f * f * 1.01) << "piece " << i;
    EXPECT_LE(std::tan(e.tilt), std::tan(l.max_tilt) * f * f * 1.01) << "piece " << i;
    EXPECT_LE(e.max_thrust - l.gravity, (l.max_thrust - l.gravity) * f * f * 1.01) << "piece " << i;
    EXPECT_LE(l.gravity - e.min_thrust, (l.gravity - l.min_thrust) * f * f * 1.01) << "piece " << i;
  }
}

std::vector<Vector3> randomPath(std::mt19937& rng)
{
  std::uniform_real_distribution<double> xy(-15.0, 15.0);
  std::uniform_real_distribution<double> z(1.0, 5.0);
  std::uniform_int_distribution<int> count(2, 7);
  std::vector<Vector3> path;
  const int n = count(rng);
  for (int i = 0; i < n; ++i) {
    path.emplace_back(xy(rng), xy(rng), z(rng));
  }
  return path;
}

TEST(Generator, RandomPathsKeepEveryLimitAndTheCorridorAndEndAtRestOnTheirEnd)
{
  // GIVEN random polylines, and random limits of a slow and of a fast vehicle
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> speed(1.0, 12.0);
  std::uniform_real_distribution<double> accel(1.5, 7.0);
  for (int trial = 0; trial < 40; ++trial) {
    GeneratorConfig c = fastConfig();
    c.limits.max_speed = speed(rng);
    c.limits.max_acceleration = accel(rng);
    const Generator generator(c);
    const std::vector<Vector3> path = randomPath(rng);
    // WHEN a trajectory is made from rest on the first point
    const GenerateResult r = generator.generate(2.0, State{path.front()}, path);
    // THEN it keeps the limits, keeps to the corridor, starts there and ends at rest at the end
    ASSERT_EQ(r.status, GenerateStatus::kOk) << "trial " << trial << ": " << r.why;
    expectWithin(r.trajectory, c);
    EXPECT_LE(largestDeviation(r.trajectory, {path}), c.corridor * 1.01) << trial;
    EXPECT_DOUBLE_EQ(r.trajectory.startTime(), 2.0);
    EXPECT_LT((r.trajectory.at(2.0).p - path.front()).norm(), 1e-8);
    const State end = r.trajectory.pieces().back().at(r.trajectory.pieces().back().duration);
    EXPECT_LT((end.p - path.back()).norm(), 1e-8);
    EXPECT_LT(end.v.norm() + end.a.norm() + end.j.norm(), 1e-6);
  }
}

TEST(Generator, ANewTrajectoryFromOneFlownContinuesItsPositionVelocityAccelerationAndJerk)
{
  // GIVEN a trajectory flown along one path, and at t1 a new path that follows it for a stretch
  // and then turns off (as a replan does that sees something ahead)
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> turn(-1.0, 1.0);
  std::uniform_real_distribution<double> ahead(1.0, 2.5);
  const GeneratorConfig c = fastConfig();
  const Generator generator(c);
  int stitched = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const std::vector<Vector3> first = randomPath(rng);
    const GenerateResult a = generator.generate(0.0, State{first.front()}, first);
    ASSERT_EQ(a.status, GenerateStatus::kOk) << a.why;
    const double t1 = 0.3 * a.trajectory.endTime();
    const State s = a.trajectory.at(t1);
    std::vector<Vector3> old_ahead;
    for (double t = t1; t <= a.trajectory.endTime(); t += 0.05) {
      old_ahead.push_back(a.trajectory.at(t).p);
    }
    const double keep = t1 + ahead(rng);
    std::vector<Vector3> second;
    for (double t = t1; t <= keep; t += 0.25) {
      second.push_back(a.trajectory.at(t).p);
    }
    const Vector3 heading = a.trajectory.at(keep).v.normalized();
    const double angle = turn(rng);  // up to a radian off the old direction
    const Vector3 off(std::cos(angle) * heading.x() - std::sin(angle) * heading.y(),
                      std::sin(angle) * heading.x() + std::cos(angle) * heading.y(), 0.0);
    second.push_back(second.back() + 15.0 * off);
    // WHEN a trajectory is made from that state, the old curve ahead known free as well
    const GenerateResult b = generator.generate(t1, s, second, {old_ahead});
    if (b.status != GenerateStatus::kOk) {
      continue;  // too hard a turn for the speed: the old one is flown on
    }
    ++stitched;
    // THEN at the stitch the two agree in every derivative the controller uses
    const State n = b.trajectory.at(t1);
    EXPECT_LT((n.p - s.p).norm(), 1e-9);
    EXPECT_LT((n.v - s.v).norm(), 1e-7 * (1.0 + s.v.norm()));
    EXPECT_LT((n.a - s.a).norm(), 1e-6 * (1.0 + s.a.norm()));
    EXPECT_LT((n.j - s.j).norm(), 1e-5 * (1.0 + s.j.norm()));
    // ... and just after it nothing jumps either
    const State later = b.trajectory.at(t1 + 1e-4);
    EXPECT_LT((later.a - s.a).norm(), 0.05);
    expectWithin(b.trajectory, c, 1.1);  // the turn onto the new path may ask a little more
    EXPECT_LE(largestDeviation(b.trajectory, {second, old_ahead}), c.corridor * 1.01);
  }
  EXPECT_GE(stitched, 25);  // nearly every such path is taken
}

TEST(Generator, AStraightLineIsFlownNearTheTimeOptimalPace)
{
  // GIVEN 40 m straight, from rest to rest, at 10 m/s and 6 m/s²
  const GeneratorConfig c = fastConfig();
  const Generator generator(c);
  const std::vector<Vector3> line{Vector3(0, 0, 2), Vector3(40, 0, 2)};
  const GenerateResult r = generator.generate(0.0, State{line.front()}, line);
  ASSERT_EQ(r.status, GenerateStatus::kOk) << r.why;
  // THEN within 1.4 times the bound no vehicle with those speed and acceleration limits beats
  // (accelerate, cruise, brake: 40/10 + 10/6 s), and at least as long
  const double bound = 40.0 / 10.0 + 10.0 / 6.0;
  EXPECT_GE(r.trajectory.duration(), bound);
  EXPECT_LE(r.trajectory.duration(), 1.4 * bound);
  EXPECT_GT(extremes(r.trajectory).speed, 0.9 * c.limits.max_speed);
}

TEST(Generator, FeedForwardIsTheDerivativeOfTheReference)
{
  std::mt19937 rng(31);
  const Generator generator(fastConfig());
  const std::vector<Vector3> path = randomPath(rng);
  const GenerateResult r = generator.generate(0.0, State{path.front()}, path);
  ASSERT_EQ(r.status, GenerateStatus::kOk);
  const double h = 1e-5;
  for (double t = 0.05; t < r.trajectory.endTime() - 0.05; t += 0.137) {
    const State s = r.trajectory.at(t);
    const State before = r.trajectory.at(t - h);
    const State after = r.trajectory.at(t + h);
    EXPECT_LT(((after.p - before.p) / (2 * h) - s.v).norm(), 1e-4);
    EXPECT_LT(((after.v - before.v) / (2 * h) - s.a).norm(), 1e-3);
    EXPECT_LT(((after.a - before.a) / (2 * h) - s.j).norm(), 1e-2);
  }
}

TEST(Generator, TooShortAPathToStopOnAtSpeedIsInfeasible)
{
  // GIVEN a vehicle at 10 m/s, and a path that ends 2 m ahead (braking needs about 8)
  const Generator generator(fastConfig());
  const State s{Vector3(0, 0, 2), Vector3(10, 0, 0)};
  const GenerateResult r = generator.generate(0.0, s, {Vector3(0, 0, 2), Vector3(2, 0, 2)});
  // THEN it says so, rather than overshoot the end
  EXPECT_EQ(r.status, GenerateStatus::kInfeasible);
  EXPECT_FALSE(r.why.empty());
  EXPECT_TRUE(r.trajectory.empty());
}

TEST(Generator, AStopBrakesAlongTheCurveFlownAndComesToRestSoonerThanItsEnd)
{
  // GIVEN a fast trajectory along a bending path, flown to its cruise
  const GeneratorConfig c = fastConfig();
  const Generator generator(c);
  const std::vector<Vector3> path{Vector3(0, 0, 2), Vector3(30, 0, 2), Vector3(45, 12, 3), Vector3(70, 12, 3)};
  const GenerateResult r = generator.generate(0.0, State{path.front()}, path);
  ASSERT_EQ(r.status, GenerateStatus::kOk) << r.why;
  double t = 0.0;
  while (r.trajectory.at(t).v.norm() < 8.0) {
    t += 0.01;
  }
  const State s = r.trajectory.at(t);
  // WHEN it stops there
  const GenerateResult stop = generator.stop(r.trajectory, t);
  ASSERT_EQ(stop.status, GenerateStatus::kOk) << stop.why;
  // THEN it continues the state, keeps the limits and the curve, and is at rest within about
  // the braking distance (v²/2a at the planning share of the acceleration, and the jerk's turn)
  const State first = stop.trajectory.at(t);
  EXPECT_LT((first.p - s.p).norm() + (first.v - s.v).norm() + (first.a - s.a).norm(), 1e-6);
  expectWithin(stop.trajectory, c);
  std::vector<Vector3> curve;
  for (double u = t; u <= r.trajectory.endTime(); u += 0.01) {
    curve.push_back(r.trajectory.at(u).p);
  }
  EXPECT_LE(largestDeviation(stop.trajectory, {curve}), c.corridor * 1.01);
  const double braked = stop.trajectory.length(t, stop.trajectory.endTime());
  const double v = s.v.norm();
  EXPECT_LT(braked, 1.5 * (v * v / (2.0 * 0.6 * c.limits.max_acceleration) + v * c.limits.max_acceleration /
                                                                                 c.limits.max_jerk) + 1.0);
  EXPECT_LT(stop.trajectory.endTime(), r.trajectory.endTime());
  const State end = stop.trajectory.at(stop.trajectory.endTime() + 1.0);
  EXPECT_EQ(end.v, Vector3::Zero());
}

TEST(Generator, AStopNearTheSpeedLimitIsNeverRefusedForItsSplinesOvershoot)
{
  // GIVEN a slow trajectory (the control's 2 m/s, braking at 4 m/s²) along a gentle zigzag,
  // taken over from one flown and speeding up to its limit, then cruising at it
  const GeneratorConfig c = brakingConfig();
  const Generator generator(c);
  std::mt19937 rng(59);
  std::uniform_real_distribution<double> side(-0.3, 0.3);
  std::vector<Vector3> path{Vector3(0, 0, 2)};
  for (int k = 1; k <= 8; ++k) {
    path.emplace_back(2.5 * k, side(rng), 2.0);
  }
  const State start{path.front(), Vector3(1.75, -0.18, 0.0), Vector3(1.74, -0.46, -0.09), Vector3::Zero()};
  const GenerateResult r = generator.generate(0.0, start, path);
  ASSERT_EQ(r.status, GenerateStatus::kOk) << r.why;
  // WHEN it stops at any instant with room ahead to brake in (2 s of flight left)
  int stops = 0;
  for (double t = 0.0; t < r.trajectory.endTime() - 2.0; t += 0.013) {
    const GenerateResult stop = generator.stop(r.trajectory, t);
    ASSERT_EQ(stop.status, GenerateStatus::kOk) << stop.why;
    // THEN it is at rest within a second and a half, sooner than the trajectory would be,
    // never faster than 5 % over the limit (the stop's allowance for its spline)
    EXPECT_LT(stop.trajectory.endTime(), t + 1.5) << "stop at " << t << ": " << stop.why;
    EXPECT_LE(extremes(stop.trajectory, c.limits.gravity, 64).speed, 1.05 * c.limits.max_speed * 1.001);
    ++stops;
  }
  EXPECT_GT(stops, 100);
}

TEST(Generator, AShortHopFromRestIsAlwaysFlownWithinTheLimits)
{
  // GIVEN a vehicle at rest and a path a few centimetres long (a known-free stretch that barely
  // grew, a nudge to a goal): too short for a time law, a single piece from rest to rest
  const GeneratorConfig c = fastConfig();
  const Generator generator(c);
  for (const double length : {0.005, 0.02, 0.05, 0.1, 0.2, 0.29}) {
    const std::vector<Vector3> path{Vector3(1, 2, 3), Vector3(1, 2, 3) + length * Vector3(0.6, 0.0, 0.8)};
    const GenerateResult r = generator.generate(0.0, State{path.front()}, path);
    ASSERT_EQ(r.status, GenerateStatus::kOk) << length << ": " << r.why;
    expectWithin(r.trajectory, c);
    const State end = r.trajectory.pieces().back().at(r.trajectory.pieces().back().duration);
    EXPECT_LT((end.p - path.back()).norm(), 1e-9);
  }
}

TEST(Generator, AtRestOnThePointItIsToBeItStays)
{
  const Generator generator(fastConfig());
  const GenerateResult r = generator.generate(1.0, State{Vector3(1, 2, 3)}, {Vector3(1, 2, 3)});
  ASSERT_EQ(r.status, GenerateStatus::kOk);
  EXPECT_EQ(r.trajectory.at(5.0).p, Vector3(1, 2, 3));
}

TEST(Generator, RefusesNonFiniteInputAndConfigurationsOutsideTheirRange)
{
  const Generator generator(fastConfig());
  EXPECT_EQ(generator.generate(0.0, State{}, {}).status, GenerateStatus::kInvalidInput);
  EXPECT_EQ(generator.generate(0.0, State{}, {Vector3(std::nan(""), 0, 0)}).status, GenerateStatus::kInvalidInput);
  GeneratorConfig bad = fastConfig();
  bad.limits.max_speed = 0.0;
  EXPECT_THROW(Generator{bad}, std::invalid_argument);
  bad = fastConfig();
  bad.corner_deviation = 2.0 * bad.corridor;
  EXPECT_THROW(Generator{bad}, std::invalid_argument);
  bad = fastConfig();
  bad.limits.max_thrust = 5.0;  // less than the weight
  try {
    Generator{bad};
    FAIL() << "a thrust below the weight was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_thrust"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace quad::trajectory
