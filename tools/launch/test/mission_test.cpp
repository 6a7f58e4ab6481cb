// SPDX-License-Identifier: BSD-3-Clause
// The mission tracker: success, failure and the figures of the summary.
#include "quad/launch/mission.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::launch {
namespace {

using geometry::Vector3;

world::World world()
{
  // A 10 m flight along x past one sphere of radius 1 m at (5, 3, 2).
  world::Sphere s{Vector3(5, 3, 2), 1.0};
  return world::World({Vector3(-1, -5, 0), Vector3(12, 5, 5)}, Vector3(0, 0, 0), Vector3(10, 0, 2),
                      {world::Obstacle::makeSphere(s)});
}

Mission mission(bool land)
{
  Mission m;
  m.enabled = true;
  m.tolerance_m = 0.3;
  m.land = land;
  m.timeout_s = 30.0;
  return m;
}

/// Flies the straight line from start to goal at 1 m/s, 10 states a second.
void fly(MissionTracker& t, double t0, Eigen::Vector3d from, Eigen::Vector3d to)
{
  const double length = (to - from).norm();
  for (double s = 0; s <= length + 1e-9; s += 0.1) {
    t.onState(t0 + s, from + (to - from) * (s / length));
  }
}

TEST(MissionTracker, LandingAtTheGoalWithoutCollisionIsASuccess)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.25);
  t.onMode(0.0, "TAKEOFF");
  fly(t, 0.0, {0, 0, 0}, {0, 0, 2});
  t.onMode(2.0, "MISSION");
  t.onPath(2.0, 1);
  t.onPath(2.2, 1);  // a repeat is not a new path
  t.onPath(2.4, 2);
  fly(t, 2.0, {0, 0, 2}, {10, 0, 2});
  EXPECT_FALSE(t.finished());
  t.onMode(12.0, "LAND");
  fly(t, 12.0, {10, 0, 2}, {10, 0, 0});
  t.onMode(14.0, "IDLE");
  ASSERT_TRUE(t.finished());
  const MissionSummary s = t.summary(7.0);
  EXPECT_TRUE(s.success) << s.outcome;
  EXPECT_EQ(s.outcome, "landed at the goal");
  EXPECT_NEAR(s.path_length_m, 14.0, 1e-6);
  EXPECT_NEAR(s.straight_line_m, std::hypot(10.0, 2.0), 1e-12);
  EXPECT_EQ(s.paths, 2);
  EXPECT_EQ(s.mode_changes, 4);
  // Closest to the sphere: the point (5, 0, 2), 3 m from its centre: 3 − 1 − 0.25.
  EXPECT_NEAR(s.min_clearance_m, 1.75, 1e-9);
  EXPECT_NE(toJson(s).find("\"success\": true"), std::string::npos);
  // No mapper's stats heard: its overruns are unknown, not zero
  EXPECT_FALSE(s.map_overruns.has_value());
  EXPECT_NE(toJson(s).find("\"map_overruns\": null"), std::string::npos);
  EXPECT_FALSE(s.path_overruns.has_value());
}

TEST(MissionTracker, TheMappersAndThePlannersOverrunsAreTheirNewestCountsInTheSummary)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.25);
  // GIVEN the mapper's stats, counting since its start, one of them overtaken by a newer one
  t.onMapStats(0);
  t.onMapStats(3);
  t.onMapStats(2);
  // THEN the summary holds the newest count, in its JSON and its text, and no planner's
  MissionSummary s = t.summary(1.0);
  ASSERT_TRUE(s.map_overruns.has_value());
  EXPECT_EQ(*s.map_overruns, 3U);
  EXPECT_NE(toJson(s).find("\"map_overruns\": 3"), std::string::npos) << toJson(s);
  EXPECT_NE(toText(s).find("map updates over the mapper's budget: 3"), std::string::npos) << toText(s);
  EXPECT_EQ(toText(s).find("paths over the planner's budget"), std::string::npos) << toText(s);
  // AND GIVEN the planner's paths alike THEN the same for its count
  t.onPathOverruns(1);
  t.onPathOverruns(4);
  t.onPathOverruns(2);
  s = t.summary(1.0);
  ASSERT_TRUE(s.path_overruns.has_value());
  EXPECT_EQ(*s.path_overruns, 4U);
  EXPECT_NE(toJson(s).find("\"path_overruns\": 4"), std::string::npos) << toJson(s);
  EXPECT_NE(toText(s).find("paths over the planner's budget: 4"), std::string::npos) << toText(s);
}

TEST(MissionTracker, TheDepthToCommandLatencyIsTheMissionsTrajectoriesMedianAndMost)
{
  const auto w = world();
  MissionTracker t(mission(false), w, 0.25);
  // GIVEN a trajectory taken while taking off: not the mission's
  t.onMode(0.0, "TAKEOFF");
  t.onTrajectory(1.0, 0.2);
  EXPECT_FALSE(t.summary(1.0).depth_to_command_median_s.has_value());
  EXPECT_NE(toJson(t.summary(1.0)).find("\"depth_to_command_max_s\": null"), std::string::npos);
  // WHEN the mission's trajectories come 0.3, 0.5, 0.2 and 0.9 s after their frames, and one
  // stamped before its frame (a bad input) and one after the goal
  t.onMode(2.0, "MISSION");
  t.onTrajectory(2.3, 2.0);
  t.onTrajectory(3.5, 3.0);
  t.onTrajectory(4.2, 4.0);
  t.onTrajectory(5.9, 5.0);
  t.onTrajectory(6.0, 6.5);
  fly(t, 2.0, {0, 0, 2}, {10, 0, 2});
  ASSERT_TRUE(t.finished());
  t.onTrajectory(13.0, 10.0);
  // THEN the median is the upper middle of the four and the most is 0.9 s, in JSON and text
  const MissionSummary s = t.summary(1.0);
  ASSERT_TRUE(s.depth_to_command_median_s && s.depth_to_command_max_s);
  EXPECT_NEAR(*s.depth_to_command_median_s, 0.5, 1e-9);
  EXPECT_NEAR(*s.depth_to_command_max_s, 0.9, 1e-9);
  EXPECT_NE(toText(s).find("0.50 s (median), 0.90 s at most"), std::string::npos) << toText(s);
  // AND a fleet's is its slowest vehicle's
  MissionSummary other = s;
  other.depth_to_command_median_s = 0.7;
  other.depth_to_command_max_s.reset();
  const MissionSummary fleet = fleetSummary({s, other}, std::nullopt, 1.0);
  EXPECT_NEAR(*fleet.depth_to_command_median_s, 0.7, 1e-9);
  EXPECT_NEAR(*fleet.depth_to_command_max_s, 0.9, 1e-9);
}

TEST(MissionTracker, ACollisionFailsTheMissionEvenAtTheGoal)
{
  const auto w = world();
  MissionTracker t(mission(false), w, 0.25);
  fly(t, 0.0, {0, 0, 2}, {5, 0, 2});
  t.onCollision(5.0);
  fly(t, 5.0, {5, 0, 2}, {10, 0, 2});
  ASSERT_TRUE(t.finished());
  const auto s = t.summary(1.0);
  EXPECT_FALSE(s.success);
  EXPECT_EQ(s.collisions, 1);
}

TEST(MissionTracker, ACrashEndsTheMissionCrashedWhereItHappened)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.25);
  fly(t, 0.0, {0, 0, 2}, {4, 0, 2});
  t.onCollision(4.0);
  t.onCrash(4.0, "crashed into obstacle 0 at 1.00 m/s");
  ASSERT_TRUE(t.finished());
  t.onState(4.5, {4, 0, 2});  // it holds still where it hit
  const auto s = t.summary(1.0);
  EXPECT_FALSE(s.success);
  EXPECT_EQ(s.end, MissionEnd::kCrashed);
  EXPECT_EQ(toString(s.end), "crashed");
  EXPECT_EQ(s.outcome, "crashed into obstacle 0 at 1.00 m/s");
  EXPECT_EQ(s.collisions, 1);
  EXPECT_DOUBLE_EQ(s.sim_s, 4.0);
}

TEST(MissionTracker, NotReachingTheGoalInTimeFails)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.0);
  for (double time = 0; time <= 31.0; time += 0.5) {
    t.onState(time, {1, 0, 2});
  }
  ASSERT_TRUE(t.finished());
  const auto s = t.summary(1.0);
  EXPECT_FALSE(s.success);
  EXPECT_NE(s.outcome.find("timed out"), std::string::npos) << s.outcome;
}

TEST(MissionTracker, LandingAwayFromTheGoalFails)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.0);
  t.onMode(0.0, "MISSION");
  fly(t, 0.0, {0, 0, 2}, {4, 0, 2});
  t.onMode(4.0, "FAILSAFE_LAND");
  fly(t, 4.0, {4, 0, 2}, {4, 0, 0});
  t.onMode(6.0, "IDLE");
  ASSERT_TRUE(t.finished());
  EXPECT_FALSE(t.summary(1.0).success);
}

TEST(MissionTracker, LandingAfterLeavingTheGeofenceFailsSayingSo)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.0);
  t.onMode(0.0, "MISSION");
  fly(t, 0.0, {0, 0, 2}, {4, 0, 2});
  t.onMode(4.0, "HOVER", "the vehicle left the geofence");
  t.onMode(5.0, "RETURN", "the vehicle left the geofence");
  fly(t, 5.0, {4, 0, 2}, {0, 0, 2});
  t.onMode(9.0, "LAND", "the battery ran low");  // only the first one counts
  fly(t, 9.0, {0, 0, 2}, {0, 0, 0});
  t.onMode(11.0, "IDLE", "the vehicle left the geofence");
  ASSERT_TRUE(t.finished());
  const MissionSummary s = t.summary(1.0);
  EXPECT_FALSE(s.success);
  EXPECT_EQ(s.end, MissionEnd::kFailed);
  EXPECT_EQ(s.failure, "the vehicle left the geofence at t = 4.0 s");
}

TEST(MissionTracker, AGoalGivenUpForNoPathStaysNoPathWhenThePlannerFindsOneOnTheWayBack)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.0);
  t.onMode(0.0, "MISSION");
  fly(t, 0.0, {0, 0, 2}, {4, 0, 2});
  t.onPath(4.0, 3, "no path: known-occupied space seals the goal off");
  t.onMode(4.0, "HOVER");
  t.onMode(6.0, "RETURN");
  t.onPath(7.0, 4);  // a cell of the map flickers free while the vehicle returns
  fly(t, 6.0, {4, 0, 2}, {0, 0, 2});
  t.onMode(10.0, "LAND");
  fly(t, 10.0, {0, 0, 2}, {0, 0, 0});
  t.onMode(12.0, "IDLE");
  ASSERT_TRUE(t.finished());
  const MissionSummary s = t.summary(1.0);
  EXPECT_EQ(s.end, MissionEnd::kNoPath) << s.outcome;
  EXPECT_EQ(s.failure, "no path: known-occupied space seals the goal off");
}

TEST(MissionTracker, LandingShortWithoutAReasonFailsAsSuch)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.0);
  t.onMode(0.0, "MISSION");
  t.onPath(0.0, 3, "no path: known-occupied space seals the goal off");
  fly(t, 0.0, {0, 0, 2}, {4, 0, 2});
  t.onPath(4.0, 4);  // the planner found a way again and the mission went on
  t.onMode(4.0, "LAND");
  fly(t, 4.0, {4, 0, 2}, {4, 0, 0});
  t.onMode(6.0, "IDLE");
  ASSERT_TRUE(t.finished());
  const MissionSummary s = t.summary(1.0);
  EXPECT_EQ(s.end, MissionEnd::kFailed) << s.outcome;
  EXPECT_EQ(s.failure, "landed short of the goal");
}

TEST(GoalProblem, AGoalOrStartOutsideTheGeofenceIsNamed)
{
  const auto w = world();  // start (0, 0, 0), goal (10, 0, 2)
  common::Geofence fence;
  EXPECT_FALSE(goalProblem(w, 0.3, fence).has_value());
  fence.min = {-1, -5, -1};
  fence.max = {8, 5, 5};
  EXPECT_EQ(goalProblem(w, 0.3, fence), "the goal (10, 0, 2) is outside the geofence (-1, -5, -1) ... (8, 5, 5)");
  fence.min = {1, -5, -1};
  fence.max = {11, 5, 5};
  EXPECT_EQ(goalProblem(w, 0.3, fence), "the start (0, 0, 0) is outside the geofence (1, -5, -1) ... (11, 5, 5)");
}

TEST(FleetProblems, StartsOutsideTheWorldInAnObstacleOrInContactAreNamed)
{
  const auto w = world();  // bounds (-1, -5, 0) ... (12, 5, 5), a sphere of 1 m at (5, 3, 2)
  std::vector<FleetMember> fleet(3);
  fleet[0] = {1, {0, 0, 0}, std::nullopt, {}};
  fleet[1] = {2, {0, 2, 0}, std::array<double, 3>{10, 2, 2}, {}};
  fleet[2] = {3, {0, -2, 0}, std::nullopt, {}};
  const std::vector<double> radii{0.3, 0.3, 0.3};
  EXPECT_TRUE(fleetProblems(w, fleet, radii).empty());
  EXPECT_EQ(memberWorld(w, fleet[1]).goal(), Vector3(10, 2, 2));
  EXPECT_EQ(memberWorld(w, fleet[0]).goal(), w.goal());

  fleet[1].start = {0, 0.5, 0};  // 0.5 m from vehicle 1: two spheres of 0.3 m overlap
  fleet[2].start = {5, 3, 1.5};  // inside the sphere
  auto p = fleetProblems(w, fleet, radii);
  ASSERT_EQ(p.size(), 2U);
  EXPECT_EQ(p[0], "vehicles[1] (id 2): its start is 0.10 m into vehicles[0] (id 1)'s: the two vehicles would start in contact");
  EXPECT_EQ(p[1], "vehicles[2] (id 3): the start (5, 3, 1.5) lies inside obstacle 0");
  fleet[1].start = {0, 2, 0};
  fleet[2].start = {0, -2, 0};
  fleet[2].goal = std::array<double, 3>{5, 3, 2};
  fleet[1].start = {20, 2, 0};
  p = fleetProblems(w, fleet, radii);
  ASSERT_EQ(p.size(), 2U);
  EXPECT_EQ(p[0], "vehicles[1] (id 2): the start (20, 2, 0) is outside the world's bounds");
  EXPECT_EQ(p[1], "vehicles[2] (id 3): the goal (5, 3, 2) lies inside obstacle 0");
}

/// One vehicle's summary, as a tracker gives it.
MissionSummary vehicleSummary(std::uint32_t id, MissionEnd end, double length, std::optional<double> optimum)
{
  MissionSummary s;
  s.vehicle_id = id;
  s.end = end;
  s.success = end == MissionEnd::kSuccess;
  s.failure = s.success ? "" : "failure " + std::to_string(id);
  s.path_length_m = length;
  s.straight_line_m = length - 1.0;
  s.optimum_m = optimum;
  s.sim_s = 10.0 * id;
  s.collisions = static_cast<int>(id) - 1;
  s.min_clearance_m = 1.0 / id;
  return s;
}

TEST(FleetSummary, TheFleetSucceedsWhenEveryVehicleDoesAndSumsOrBoundsTheirFigures)
{
  MissionSummary s = fleetSummary({vehicleSummary(1, MissionEnd::kSuccess, 10.0, 9.0),
                                   vehicleSummary(2, MissionEnd::kSuccess, 20.0, 18.0)},
                                  0.8, 5.0);
  EXPECT_TRUE(s.success);
  EXPECT_EQ(s.end, MissionEnd::kSuccess);
  EXPECT_EQ(s.outcome, "2 of 2 vehicles reached their goals");
  EXPECT_EQ(s.failure, "");
  EXPECT_DOUBLE_EQ(s.path_length_m, 30.0);
  EXPECT_DOUBLE_EQ(*s.optimum_m, 27.0);
  EXPECT_DOUBLE_EQ(s.sim_s, 20.0);
  EXPECT_EQ(s.collisions, 1);
  EXPECT_DOUBLE_EQ(s.min_clearance_m, 0.5);
  EXPECT_DOUBLE_EQ(*s.min_separation_m, 0.8);
  ASSERT_EQ(s.vehicles.size(), 2U);
  EXPECT_EQ(s.vehicles[1].vehicle_id, 2U);
  const std::string json = toJson(s);
  EXPECT_NE(json.find("\"min_separation_m\": 0.8"), std::string::npos) << json;
  EXPECT_NE(json.find("\"vehicle_id\": 2"), std::string::npos) << json;
  EXPECT_FALSE(s.map_overruns.has_value());  // no vehicle's mapper was heard
  // Each vehicle's mapper heard: the fleet's overruns are theirs summed
  MissionSummary a = vehicleSummary(1, MissionEnd::kSuccess, 10.0, 9.0);
  MissionSummary b = vehicleSummary(2, MissionEnd::kSuccess, 20.0, 18.0);
  a.map_overruns = 2;
  b.map_overruns = 5;
  b.path_overruns = 3;  // a's planner unheard
  EXPECT_EQ(fleetSummary({a, b}, 0.8, 5.0).map_overruns, std::optional<std::uint64_t>(7));
  EXPECT_EQ(fleetSummary({a, b}, 0.8, 5.0).path_overruns, std::optional<std::uint64_t>(3));

  // One vehicle without a path and one failed: the fleet failed, naming both; no total optimum.
  s = fleetSummary({vehicleSummary(1, MissionEnd::kNoPath, 10.0, std::nullopt),
                    vehicleSummary(2, MissionEnd::kSuccess, 20.0, 18.0),
                    vehicleSummary(3, MissionEnd::kFailed, 5.0, 4.0)},
                   std::nullopt, 5.0);
  EXPECT_FALSE(s.success);
  EXPECT_EQ(s.end, MissionEnd::kFailed);
  EXPECT_EQ(s.outcome, "1 of 3 vehicles reached their goals");
  EXPECT_EQ(s.failure, "vehicle 1: failure 1; vehicle 3: failure 3");
  EXPECT_FALSE(s.optimum_m.has_value());
  // Only no-path ends besides successes: the fleet's end is no path.
  s = fleetSummary({vehicleSummary(1, MissionEnd::kNoPath, 10.0, std::nullopt),
                    vehicleSummary(2, MissionEnd::kSuccess, 20.0, 18.0)},
                   std::nullopt, 5.0);
  EXPECT_EQ(s.end, MissionEnd::kNoPath);
}

/// A flight's samples, each kind in order of its stamps: states at 100 Hz (climb, cruise to the
/// goal, landing), the controller's modes, a path every 0.2 s, a trajectory 0.15 s after each.
struct Samples {
  std::vector<std::pair<double, Eigen::Vector3d>> states;
  std::vector<std::pair<double, std::string>> modes;
  std::vector<std::pair<double, std::uint32_t>> paths;
  std::vector<std::pair<double, double>> trajectories;  // (t, depth frame's t)
};

Samples flight()
{
  Samples f;
  const auto leg = [&](double t0, double t1, Eigen::Vector3d a, Eigen::Vector3d b) {
    for (double t = t0; t < t1 - 1e-9; t += 0.01) {
      f.states.emplace_back(t, a + (b - a) * ((t - t0) / (t1 - t0)));
    }
  };
  leg(0.0, 2.0, {0, 0, 0}, {0, 0, 2});
  leg(2.0, 12.0, {0, 0, 2}, {10, 0, 2});
  leg(12.0, 14.0, {10, 0, 2}, {10, 0, 0});
  f.states.emplace_back(14.0, Eigen::Vector3d(10, 0, 0));
  f.modes = {{0.0, "TAKEOFF"}, {2.0, "MISSION"}, {12.0, "LAND"}, {14.0, "IDLE"}};
  for (int k = 0; k < 80; ++k) {
    f.paths.emplace_back(1.0 + 0.2 * k, static_cast<std::uint32_t>(1 + k / 2));  // each version twice
    f.trajectories.emplace_back(1.15 + 0.2 * k + 0.001 * (k % 7), 1.0 + 0.2 * k);
  }
  return f;
}

/// The samples fed as the launcher's observer takes them: every so often, each kind's samples
/// up to a lag of its own (drawn from `seed`), the states first, then the modes, paths and
/// trajectories. Seed 0: all of a kind at once, in stamp order, the kinds merged by stamp.
MissionSummary summaryOf(const Samples& f, unsigned seed)
{
  const auto w = world();
  MissionTracker t(mission(true), w, 0.25);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lag(0.0, 0.5);
  std::size_t s = 0, m = 0, p = 0, j = 0;
  for (double now = 0.0; s < f.states.size() || m < f.modes.size() || p < f.paths.size() || j < f.trajectories.size();
       now += 0.05) {
    const auto upTo = [&](double stamp) { return seed == 0 ? stamp <= now : stamp <= now - lag(rng) || now > 30.0; };
    for (; s < f.states.size() && upTo(f.states[s].first); ++s) {
      t.onState(f.states[s].first, f.states[s].second);
    }
    for (; m < f.modes.size() && upTo(f.modes[m].first); ++m) {
      t.onMode(f.modes[m].first, f.modes[m].second);
    }
    for (; p < f.paths.size() && upTo(f.paths[p].first); ++p) {
      t.onPath(f.paths[p].first, f.paths[p].second);
    }
    for (; j < f.trajectories.size() && upTo(f.trajectories[j].first); ++j) {
      t.onTrajectory(f.trajectories[j].first, f.trajectories[j].second);
    }
  }
  return t.summary(1.0);
}

TEST(MissionTracker, TheSameSamplesGiveTheSameSummaryHoweverTheirKindsInterleave)
{
  const Samples f = flight();
  const MissionSummary merged = summaryOf(f, 0);
  ASSERT_TRUE(merged.success) << merged.outcome;
  ASSERT_TRUE(merged.time_to_goal_s && merged.average_speed_mps && merged.depth_to_command_max_s);
  // the mission from its mode at 2 s to the goal's tolerance (0.3 m) before (10, 0, 2)
  EXPECT_NEAR(*merged.time_to_goal_s, 9.7, 0.011);
  EXPECT_NEAR(*merged.average_speed_mps, 1.0, 0.01);
  EXPECT_EQ(merged.paths, 33);  // every version first published up to the landing's end, once
  EXPECT_NEAR(merged.sim_s, 14.0, 1e-9);
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const MissionSummary s = summaryOf(f, seed);
    EXPECT_EQ(toJson(s), toJson(merged)) << "seed " << seed;
  }
}

}  // namespace
}  // namespace quad::launch
