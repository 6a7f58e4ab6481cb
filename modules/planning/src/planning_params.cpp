#include "quad/planning/planning_params.hpp"

#include <algorithm>

namespace quad::planning {

common::ParamSchema planningSchema()
{
  common::ParamSchema s;
  s.addString("world", "worlds/demo.yaml", {}, "world file whose bounds the lattice covers")
      .addString("vehicle", "vehicles/x500.yaml", {}, "vehicle file (its radius inflates obstacles)")
      .addDouble("safety_margin", 0.3, 0.0, 10.0, "m", "added to the vehicle radius")
      .addDouble("ground_clearance", 1.0, 0.0, 1e3, "m", "lowest cell centres above the world's floor")
      .addDouble("altitude.min", -1e4, -1e4, 1e4, "m", "an optional band: lowest cell centres planned through")
      .addDouble("altitude.max", 1e4, -1e4, 1e4, "m", "an optional band: highest cell centres planned through")
      .addDouble("known_free.radius", 0.2, 0.0, 10.0, "m",
                 "around the path's centre line, every voxel must be known free for the follower to fly it")
      .addDouble("known_free.horizon", 8.0, 0.0, 1e3, "m",
                 "path length checked for known-free space; 0: fly unknown space like free space")
      .addDouble("resolution", 0.2, 0.01, 10.0, "m", "lattice cell: the mapper's map.resolution")
      .addInt("connectivity", 26, 6, 26, "", "6, 18 or 26 neighbours")
      .addBool("unknown_traversable", true, "plan through unknown space")
      .addDouble("replan_period", 0.2, 0.01, 60.0, "s", "sim time between replans")
      .addDouble("republish_period", 0.5, 0.01, 60.0, "s",
                 "sim time between repeats of an unchanged path (at most half the path contract's deadline)")
      .addInt("max_expansions", 200000, 1, 100000000, "", "replan budget per cycle")
      .addInt("map_frames_behind", 5, 1, 1000, "",
              "depth frames the map may lag the camera before paths stop (a stalled mapper)");
  return s;
}

std::filesystem::path worldFileOf(const common::Params& params)
{
  return common::configPath(params, "world", QUAD_CONFIG_DIR);
}

std::filesystem::path vehicleFileOf(const common::Params& params)
{
  return common::configPath(params, "vehicle", QUAD_CONFIG_DIR);
}

PlanningParams planningParamsFrom(const common::Params& p, const Vector3& world_min, const Vector3& world_max,
                                  double vehicle_radius)
{
  PlanningParams c;
  c.resolution = p.getDouble("resolution");
  c.planner.vehicle_radius = vehicle_radius + p.getDouble("safety_margin");
  // The whole volume the vehicle may fly in: the world's box less the inflation radius at the
  // sides and the top, from the ground clearance up; an altitude band clips it further.
  const Vector3 inset = Vector3::Constant(c.planner.vehicle_radius);
  c.bounds_min = world_min + inset;
  c.bounds_max = world_max - inset;
  c.bounds_min.z() = world_min.z() + p.getDouble("ground_clearance");
  const double lo = p.getDouble("altitude.min");
  const double hi = p.getDouble("altitude.max");
  if (lo > hi) {
    throw common::ConfigError({common::configProblem(p.origin(), "altitude.min", lo, "above altitude.max")});
  }
  c.bounds_min.z() = std::max(c.bounds_min.z(), lo);
  c.bounds_max.z() = std::min(c.bounds_max.z(), hi);
  for (int axis = 0; axis < 3; ++axis) {
    if (c.bounds_min[axis] + c.resolution > c.bounds_max[axis]) {
      const char* key = axis == 2 ? "ground_clearance" : "safety_margin";
      throw common::ConfigError({common::configProblem(
          p.origin(), key, p.getDouble(key),
          "leaves less than a cell of the world's bounds to plan in (with the altitude band, if any)")});
    }
  }
  c.known_space.radius = p.getDouble("known_free.radius");
  c.known_space.horizon = p.getDouble("known_free.horizon");
  // The vehicle's own volume is free (it is there) but partly behind its camera.
  c.known_space.own_radius = vehicle_radius + c.resolution;
  c.planner.connectivity = static_cast<int>(p.getInt("connectivity"));
  if (c.planner.connectivity != 6 && c.planner.connectivity != 18 && c.planner.connectivity != 26) {
    throw common::ConfigError({common::configProblem(p.origin(), "connectivity", std::int64_t{c.planner.connectivity},
                                                     "expected 6, 18 or 26")});
  }
  c.planner.unknown_traversable = p.getBool("unknown_traversable");
  c.replan_period_s = p.getDouble("replan_period");
  c.republish_period_s = p.getDouble("republish_period");
  c.max_expansions = static_cast<std::uint64_t>(p.getInt("max_expansions"));
  c.map_frames_behind = static_cast<std::uint64_t>(p.getInt("map_frames_behind"));
  return c;
}

}  // namespace quad::planning
