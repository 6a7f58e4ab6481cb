// SPDX-License-Identifier: BSD-3-Clause
// FASTER's rule end to end on the cores, in seeded forests of the benchmark's densest kind: a
// vehicle that maps as it goes (the depth camera, the mapper, D* Lite, the known-free check,
// the follower) never commits to a state from which its stop would enter space its map does
// not know free.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include <fmt/format.h>

#include "closed_loop.hpp"
#include "quad/common/params.hpp"
#include "quad/common/yaml_input.hpp"
#include "quad/control/trajectory_follower.hpp"
#include "quad/geometry/inflation.hpp"
#include "quad/geometry/polyline.hpp"
#include "quad/mapping/mapper.hpp"
#include "quad/planning/known_space.hpp"
#include "quad/planning/planning_params.hpp"
#include "quad/planning/replan.hpp"
#include "quad/plant/sensors.hpp"
#include "quad/world/world_file.hpp"

namespace quad::control {
namespace {

using planning::Occupancy;
using planning::VoxelIndex;

constexpr double kTick = 0.004;        // [s] the control rate's period
constexpr int kTicksPerFrame = 25;     // the depth camera at 10 Hz
constexpr int kTicksPerReplan = 50;    // the planner's 0.2 s
constexpr double kCommitted = 0.4;     // [s] of a new trajectory whose every state's stop is checked
constexpr double kSample = 0.02;       // [s] between the states checked

/// The benchmark's densest forest (configs/worlds/benchmark_forest.yaml) with its trees drawn
/// from `seed`.
world::World forest(std::uint64_t seed)
{
  const std::string file = std::string(QUAD_CONFIG_DIR) + "/worlds/benchmark_forest.yaml";
  std::string text = common::readTextFile(file);
  const std::size_t at = text.find("seed: 1,");
  if (at == std::string::npos) {
    throw std::runtime_error(file + ": no 'seed: 1,' to draw other forests with");
  }
  text.replace(at, 8, fmt::format("seed: {},", seed));
  return world::parseWorld(text, file);
}

/// configs/planning.yaml's parameters, fitted to `world`.
planning::PlanningParams planningParams(const world::World& world, double vehicle_radius)
{
  const std::string file = std::string(QUAD_CONFIG_DIR) + "/planning.yaml";
  planning::PlanningParams params =
      planning::planningParamsOf(common::parseParams(common::readTextFile(file), file, planning::planningSchema()));
  planning::fitToWorld(params, world.bounds().min, world.bounds().max, vehicle_radius, file);
  return params;
}

Occupancy occupancyOf(mapping::VoxelState s)
{
  switch (s) {
    case mapping::VoxelState::kFree:
      return Occupancy::kFree;
    case mapping::VoxelState::kOccupied:
      return Occupancy::kOccupied;
    default:
      return Occupancy::kUnknown;
  }
}

/// A camera on a world-stabilised gimbal at `p`, looking at `target`.
geometry::Pose3 lookingAt(const Vector3& p, const Vector3& target)
{
  const Vector3 d = target - p;
  const double yaw = std::atan2(d.y(), d.x());
  const double pitch = std::atan2(d.z(), d.head<2>().norm());
  return {p, geometry::fromAxisAngle(Vector3::UnitZ(), yaw) * geometry::fromAxisAngle(Vector3::UnitY(), -pitch)};
}

/// What the map must say about the voxels a state's sphere (`radius` [m]) touches: known
/// free, or the vehicle's own volume at the replan that committed it (within `own` [m] of
/// `anchor`).
struct KnownFreeJudge {
  KnownFreeJudge(const planning::DStarLite& p, const Vector3& a, double own_radius, double sphere_radius)
      : planner(p), anchor(a), own(own_radius), radius(sphere_radius),
        // every voxel a sphere anywhere in the voxel at offset 0 may touch
        reach(geometry::inflationOffsets(radius + p.lattice().grid().resolution(), p.lattice().grid().resolution()))
  {
  }
  const planning::DStarLite& planner;
  Vector3 anchor;
  double own;
  double radius;
  std::vector<VoxelIndex> reach;

  /// The first voxel the sphere at `p` touches that is not known free, as words; empty when
  /// there is none.
  std::string problemAt(const Vector3& p) const
  {
    const geometry::VoxelGrid& grid = planner.lattice().grid();
    const double half = 0.5 * grid.resolution();
    const VoxelIndex at = grid.toIndex(p);
    for (const VoxelIndex& o : reach) {
      const VoxelIndex v = at + o;
      // The distance from p to the voxel's box.
      const Vector3 outside = ((p - grid.centre(v)).cwiseAbs().array() - half).max(0.0);
      if (outside.norm() > radius) {
        continue;
      }
      const Occupancy state = planner.voxelState(v);
      if (state != Occupancy::kFree && (grid.centre(v) - anchor).norm() > own) {
        return fmt::format("voxel ({}, {}, {}) is {} near ({:.2f}, {:.2f}, {:.2f})", v.x(), v.y(), v.z(),
                           state == Occupancy::kOccupied ? "occupied" : "unknown", p.x(), p.y(), p.z());
      }
    }
    return {};
  }
};

/// The trajectory just taken at `t0`, to its end, and the stop from each of its states over
/// the next kCommitted seconds: the first state whose sphere is not in known-free space, as
/// words; empty when every one is.
std::string committedProblem(const TrajectoryFollower& follower, double t0, const KnownFreeJudge& judge)
{
  TrajectoryFollower flown = follower;
  const double end = follower.trajectory().endTime();
  for (double t = t0; t <= end + kSample; t += kSample) {
    if (std::string why = judge.problemAt(flown.step(std::min(t, end)).p_W); !why.empty()) {
      return fmt::format("the trajectory at {:.2f} s: {}", t, why);
    }
  }
  for (double t = t0; t <= t0 + kCommitted; t += kSample) {
    TrajectoryFollower stopping = follower;
    stopping.step(t);
    stopping.brake(t);
    for (double s = t; !stopping.finished(s) && s < t + 10.0; s += kSample) {
      if (std::string why = judge.problemAt(stopping.step(s).p_W); !why.empty()) {
        return fmt::format("the stop from {:.2f} s, at {:.2f} s: {}", t, s, why);
      }
    }
  }
  return {};
}

TEST(StoppingRule, NoCommittedStateOfAForestFlownAt8MetresASecondCanOnlyStopOutsideKnownFreeSpace)
{
  const vehicle::VehicleParams vehicle = test::loadVehicle("x500");
  FollowerLimits limits;
  limits.max_speed = 8.0;
  limits.max_acceleration = 5.0;
  limits.max_jerk = 25.0;
  const plant::DepthCamera camera(plant::DepthCameraConfig{});
  int reached = 0;
  double top_speed = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    // GIVEN a forest of the benchmark's densest kind, unknown to the vehicle hovering at its start
    const world::World world = forest(seed);
    const planning::PlanningParams params = planningParams(world, vehicle.radius);
    planning::DStarLite planner(
        planning::Lattice(geometry::VoxelGrid(params.resolution), params.bounds_min, params.bounds_max), params.planner);
    const Vector3 goal = world.goal();
    planner.setGoal(planner.lattice().nearestCell(goal));
    mapping::MapperConfig map_config;
    map_config.resolution = params.resolution;
    map_config.coverWorld(world.bounds().min, world.bounds().max);
    mapping::Mapper mapper(map_config);
    TrajectoryFollower follower(limits, generatorConfig(limits, vehicle, GeometricGains{}.max_tilt));
    const Vector3 start(world.start().x(), world.start().y(), goal.z());
    follower.hold(start, 0.0, 0.0);
    std::mt19937_64 rng(seed);
    const auto see = [&](const geometry::Pose3& sensor) {
      const plant::DepthScan frame = camera.captureFrom(world, sensor, rng);
      mapping::Scan scan;
      scan.origin_W = sensor.p;
      scan.max_range = camera.config().max_range;
      for (const Eigen::Vector3f& p : frame.points_S) {
        scan.points_W.push_back(sensor.transform(p.cast<double>()));
      }
      for (const mapping::VoxelChange& c : mapper.integrate(scan).changes) {
        planner.updateVoxel(c.index, occupancyOf(c.state));
      }
    };
    // It has looked around where it hovers (the stack's camera looks along its climb).
    for (const Vector3& d : {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(-1, 0, 0), Vector3(0, -1, 0),
                             Vector3(0.01, 0, 1), Vector3(0.01, 0, -1)}) {
      see(lookingAt(start, start + d));
    }
    std::vector<Vector3> path;
    std::uint32_t version = 0;
    int taken = 0;
    // WHEN it flies to the goal, perfectly on its reference, mapping a depth frame every 0.1 s
    // and replanning every 0.2 s, flying each path only as far as the map knows it free
    double t = 0.0;
    for (int tick = 0; t < 60.0; ++tick) {
      t = tick * kTick;
      const Reference r = follower.step(t);
      top_speed = std::max(top_speed, r.v_W.norm());
      ASSERT_TRUE(world.contacts(r.p_W, vehicle.radius).empty())
          << "seed " << seed << ": the reference touches an obstacle at " << t << " s";
      if (tick % kTicksPerFrame == 0) {
        const Vector3 look = path.size() >= 2 ? geometry::pointAlong(path, geometry::nearestArcLength(path, r.p_W) + 3.0)
                                              : goal;
        see(lookingAt(r.p_W, (look - r.p_W).norm() > 0.5 ? look : goal));
      }
      if (tick % kTicksPerReplan != 0) {
        continue;
      }
      if ((r.p_W - goal).norm() < 0.3 && follower.finished(t)) {
        ++reached;
        break;
      }
      // The planning module's replan (replan.hpp), from where the vehicle is.
      const planning::Replan plan = planning::replanFrom(planner, r.p_W, params);
      if (plan.result.status != planning::PlanStatus::kOk) {
        continue;
      }
      path = plan.waypoints;
      const double known_free = plan.known_free;
      if (!follower.setPath(geometry::truncated(path, known_free), ++version, t)) {
        continue;  // the trajectory flown goes on: it was checked when it was taken
      }
      ++taken;
      // THEN the trajectory it commits to, and the stop from each of its next states, keep
      // the vehicle's sphere in voxels its map knows free
      const KnownFreeJudge judge{planner, r.p_W, params.known_space.own_radius, vehicle.radius};
      const std::string problem = committedProblem(follower, t, judge);
      ASSERT_TRUE(problem.empty()) << "seed " << seed << ", path " << version << " taken at " << t << " s: " << problem;
    }
    EXPECT_GT(taken, 10) << "seed " << seed;
  }
  // AND it crossed the forests, fast
  EXPECT_GE(reached, 5);
  EXPECT_GT(top_speed, 5.0);
}

}  // namespace
}  // namespace quad::control
