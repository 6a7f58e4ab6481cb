// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The known-map optimum: the planner's own search (D* Lite, the same lattice, vehicle
/// radius and safety margin) on the whole world with every obstacle known. A mission's flown
/// path is measured against it; `quad plan` prints it.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "quad/common/params.hpp"
#include "quad/planning/dstar_lite.hpp"
#include "quad/planning/planning_params.hpp"
#include "quad/world/world.hpp"

namespace quad::plan {

using geometry::Vector3;

struct KnownMapPlan {
  planning::PlanStatus status = planning::PlanStatus::kNoGoal;
  Vector3 from = Vector3::Zero();   ///< [m] the start, lifted into the lattice and out of any inflation (take-off)
  std::vector<Vector3> waypoints;   ///< [m] the shortened path from `from` to the goal
  double path_m = 0.0;              ///< [m] its length
  double climb_m = 0.0;             ///< [m] from the start up into the lattice
  double landing_m = 0.0;           ///< [m] from the goal down to what lies beneath it, when the mission lands
  double optimum_m = 0.0;           ///< [m] climb + path + landing: what a flight is compared with
  std::size_t occupied_voxels = 0;  ///< obstacle surface voxels the map was given
  std::uint64_t expansions = 0;
};

/// Gives the planner every voxel of an obstacle's surface (centre within half a voxel's
/// diagonal of it; the inside of an obstacle is a pocket no path enters) as occupied and
/// plans from the start, lifted into the lattice, to the goal. `land`: the mission lands at
/// the goal, so the descent to the floor is part of the flight.
KnownMapPlan planOnKnownMap(const world::World& world, const planning::PlanningParams& params, bool land);

/// A planning config (empty path: the schema's defaults) with `overrides` on top, and the world
/// and vehicle files it names loaded: what the planner of a run would plan with.
struct PlanningSetup {
  std::filesystem::path world_file;
  world::World world;
  planning::PlanningParams params;
};
/// Throws common::ConfigError naming the file, key or value.
PlanningSetup loadPlanningSetup(const std::filesystem::path& config, const std::vector<common::ParamOverride>& overrides);

}  // namespace quad::plan
