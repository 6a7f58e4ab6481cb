// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The planner's parameters (configs/planning.yaml), declared once: the planning node and
/// `quad plan` read them. The files they name (the world, the vehicle) are loaded by the
/// caller; this turns their box and radius into the lattice the planner searches.

#include <cstdint>
#include <filesystem>

#include "quad/common/geofence.hpp"
#include "quad/common/param_table.hpp"
#include "quad/planning/deconfliction.hpp"
#include "quad/planning/known_space.hpp"

namespace quad::planning {

struct PlanningParams {
  std::filesystem::path world_file = "worlds/demo.yaml";    ///< its box is the lattice's
  std::filesystem::path vehicle_file = "vehicles/x500.yaml";  ///< its radius inflates obstacles
  double safety_margin = 0.3;           ///< [m] added to the vehicle radius
  double ground_clearance = 1.0;        ///< [m] lowest cell centres above the world's floor
  double altitude_min = -1e4;           ///< [m] an optional band of cell centres' altitudes
  double altitude_max = 1e4;            ///< [m]
  common::Geofence geofence;            ///< the keep-in volume: no cell centre closer than the margin to its faces
  Vector3 bounds_min = Vector3::Zero();  ///< [m] the lattice's box (cell centres within it), from the above
  Vector3 bounds_max = Vector3::Zero();
  double resolution = 0.2;              ///< [m]
  PlannerConfig planner;                ///< vehicle_radius: the vehicle's plus the safety margin
  KnownSpaceCheck known_space;          ///< horizon 0: unknown space is flown like free space
  /// [m] the known-free tube's radius past the vehicle's (known_space.radius, from fitToWorld):
  /// the vehicle may stray from the path by the follower's corridor, and all of it must fly in
  /// known-free space
  double known_free_margin = 0.1;
  double replan_period_s = 0.2;         ///< [s] of sim time between replans
  double state_rate = 0.0;              ///< [Hz] of sim time, at most: the states read (the node's); 0: every one
  double republish_period_s = 0.5;      ///< [s] of sim time between repeats of an unchanged path
  std::uint64_t max_expansions = 200000;
  std::uint64_t map_frames_behind = 5;  ///< depth frames the map may lag the camera before paths stop
  FleetRule fleet;                      ///< how the vehicle gives way to the others of a fleet (not on a known map)
};

/// configs/planning.yaml: each key with its unit, range and the field it fills; the defaults
/// are PlanningParams' own.
const common::ParamTable<PlanningParams>& planningTable();
common::ParamSchema planningSchema();

/// The parameters as a file gives them, the world and vehicle files resolved; the lattice's
/// box is still to be fitted to the world (fitToWorld).
PlanningParams planningParamsOf(const common::Params& params);

/// Makes the lattice's box from the world's box (`world_min`, `world_max` [m]): less the
/// inflation radius at the sides and the top (leaving the box is a collision), from
/// `ground_clearance` above its floor, clipped to the optional altitude band and to the
/// geofence less the safety margin (the follower's deviation from the path).
/// `vehicle_radius` [m] is the vehicle's own. Throws common::ConfigError naming `origin` and
/// the key when the band is inverted or leaves less than a cell, or the connectivity is not
/// 6, 18 or 26.
void fitToWorld(PlanningParams& params, const Vector3& world_min, const Vector3& world_max, double vehicle_radius,
                const std::string& origin);

/// planningParamsOf, then fitToWorld.
PlanningParams planningParamsFrom(const common::Params& params, const Vector3& world_min, const Vector3& world_max,
                                  double vehicle_radius);

}  // namespace quad::planning
