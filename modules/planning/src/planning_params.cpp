// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/layout.hpp"
#include "quad/planning/planning_params.hpp"

#include <cmath>

#include <algorithm>

namespace quad::planning {

const common::ParamTable<PlanningParams>& planningTable()
{
  using P = PlanningParams;
  static const common::ParamTable<P> table = [] {
    common::ParamTable<P> t;
    t.path("world", [](P& p) -> std::filesystem::path& { return p.world_file; },
           "world file whose bounds the lattice covers")
        .path("vehicle", [](P& p) -> std::filesystem::path& { return p.vehicle_file; },
              "vehicle file (its radius inflates obstacles)")
        .number("safety_margin", [](P& p) -> double& { return p.safety_margin; }, {0.0, 10.0}, "m",
                "added to the vehicle radius")
        .number("ground_clearance", [](P& p) -> double& { return p.ground_clearance; }, {0.0, 1e3}, "m",
                "lowest cell centres above the world's floor")
        .number("altitude.min", [](P& p) -> double& { return p.altitude_min; }, {-1e4, 1e4}, "m",
                "an optional band: lowest cell centres planned through")
        .number("altitude.max", [](P& p) -> double& { return p.altitude_max; }, {-1e4, 1e4}, "m",
                "an optional band: highest cell centres planned through")
        .include(common::geofenceTable(), [](P& p) -> common::Geofence& { return p.geofence; })
        .number("known_free.margin", [](P& p) -> double& { return p.known_free_margin; }, {0.0, 10.0}, "m",
                "past the vehicle's radius around the path's centre line, every voxel must be known free for the "
                "follower to fly it (at least the follower's corridor)")
        .number("known_free.horizon", [](P& p) -> double& { return p.known_space.horizon; }, {0.0, 1e3}, "m",
                "path length checked for known-free space; 0: fly unknown space like free space")
        .number("resolution", [](P& p) -> double& { return p.resolution; }, {0.01, 10.0}, "m",
                "lattice cell: the mapper's map.resolution")
        .number("connectivity", [](P& p) -> int& { return p.planner.connectivity; }, {6, 26}, "",
                "6, 18 or 26 neighbours")
        .flag("unknown_traversable", [](P& p) -> bool& { return p.planner.unknown_traversable; },
              "plan through unknown space")
        .number("replan_period", [](P& p) -> double& { return p.replan_period_s; }, {0.01, 60.0}, "s",
                "sim time between replans")
        .number("state.rate", [](P& p) -> double& { return p.state_rate; }, {0.0, 1000.0}, "Hz",
                "the node's vehicle states read per second of sim time, at most (the first of each period: their "
                "writers send no more), a replan starting at one; 0: every one")
        .number("republish_period", [](P& p) -> double& { return p.republish_period_s; }, {0.01, 60.0}, "s",
                "sim time between repeats of an unchanged path (at most half the path contract's deadline)")
        .number("max_expansions", [](P& p) -> std::uint64_t& { return p.max_expansions; }, {1, 100000000}, "",
                "replan budget per cycle")
        .number("map_frames_behind", [](P& p) -> std::uint64_t& { return p.map_frames_behind; }, {1, 1000}, "",
                "depth frames the map may lag the camera before paths stop (a stalled mapper)")
        .number("fleet.separation", [](P& p) -> double& { return p.fleet.separation; }, {0.0, 100.0}, "m",
                "in a fleet: kept between this vehicle's sphere and that of every vehicle of a lower id")
        .number("fleet.lookahead", [](P& p) -> double& { return p.fleet.lookahead; }, {0.0, 1000.0}, "m",
                "in a fleet: of a lower id's newest path, from where it was published, kept out of")
        .number("fleet.path_timeout", [](P& p) -> double& { return p.fleet.path_timeout_s; }, {0.1, 60.0}, "s",
                "in a fleet: sim time after its stamp a lower id's path is kept out of");
    return t;
  }();
  return table;
}

common::ParamSchema planningSchema() { return planningTable().schema(); }

PlanningParams planningParamsOf(const common::Params& params)
{
  PlanningParams p = planningTable().read(params, common::configDir());
  common::checkGeofence(p.geofence, params.origin());
  return p;
}

void fitToWorld(PlanningParams& c, const Vector3& world_min, const Vector3& world_max, double vehicle_radius,
                const std::string& origin)
{
  c.planner.vehicle_radius = vehicle_radius + c.safety_margin;
  // The whole volume the vehicle may fly in: the world's box less the inflation radius at the
  // sides and the top, from the ground clearance up; an altitude band clips it further.
  const Vector3 inset = Vector3::Constant(c.planner.vehicle_radius);
  c.bounds_min = world_min + inset;
  c.bounds_max = world_max - inset;
  c.bounds_min.z() = world_min.z() + c.ground_clearance;
  if (c.altitude_min > c.altitude_max) {
    throw common::ConfigError({common::configProblem(origin, "altitude.min", c.altitude_min, "above altitude.max")});
  }
  c.bounds_min.z() = std::max(c.bounds_min.z(), c.altitude_min);
  c.bounds_max.z() = std::min(c.bounds_max.z(), c.altitude_max);
  // The geofence less the margin: following the path, the vehicle stays inside.
  for (int axis = 0; axis < 3; ++axis) {
    const auto i = static_cast<std::size_t>(axis);
    c.bounds_min[axis] = std::max(c.bounds_min[axis], c.geofence.min[i] + c.safety_margin);
    c.bounds_max[axis] = std::min(c.bounds_max[axis], c.geofence.max[i] - c.safety_margin);
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (c.bounds_min[axis] + c.resolution > c.bounds_max[axis]) {
      const bool vertical = axis == 2;
      throw common::ConfigError({common::configProblem(
          origin, vertical ? "ground_clearance" : "safety_margin", vertical ? c.ground_clearance : c.safety_margin,
          "leaves less than a cell of the world's bounds to plan in (with the altitude band and the geofence, if any)")});
    }
  }
  // What the follower may fly: the vehicle's volume, anywhere within its corridor of the path.
  // The check reads the voxels around each voxel the path passes (whose centre may lie half a
  // voxel's diagonal off the path): within the inflation, or a path along its edge would never
  // be known free.
  c.known_space.radius = vehicle_radius + c.known_free_margin;
  const double slack = 0.5 * std::sqrt(3.0) * c.resolution;
  // The vehicle's own volume is free (it is there) but partly behind its camera, and so is the
  // tube the check reads around the voxel it is in: it flew there inside such tubes, known free,
  // but after a turn their sides may lie where the camera never looked (a vehicle stopped
  // there would wait for them forever).
  c.known_space.own_radius = std::max(vehicle_radius + c.resolution, c.known_space.radius + slack);
  if (c.known_space.horizon > 0.0 && c.known_space.radius + slack > c.planner.vehicle_radius) {
    throw common::ConfigError({common::configProblem(
        origin, "known_free.margin", c.known_free_margin,
        "with the vehicle's radius and half a voxel's diagonal it reaches past the safety margin (" +
            common::formatValue(c.safety_margin) + " m): paths along obstacles would never be known free")});
  }
  if (c.planner.connectivity != 6 && c.planner.connectivity != 18 && c.planner.connectivity != 26) {
    throw common::ConfigError({common::configProblem(origin, "connectivity", std::int64_t{c.planner.connectivity},
                                                     "expected 6, 18 or 26")});
  }
}

PlanningParams planningParamsFrom(const common::Params& p, const Vector3& world_min, const Vector3& world_max,
                                  double vehicle_radius)
{
  PlanningParams c = planningParamsOf(p);
  fitToWorld(c, world_min, world_max, vehicle_radius, p.origin());
  return c;
}

}  // namespace quad::planning
