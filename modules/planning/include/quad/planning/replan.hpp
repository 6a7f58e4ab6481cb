// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One replan as the planning module makes it: from where the vehicle will be, the D* Lite
/// search, the shortcut path anchored at the vehicle, and how much of it the follower may fly
/// (FASTER's rule: only as far as the map knows it free, and no further than the horizon).

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "quad/planning/dstar_lite.hpp"
#include "quad/planning/planning_params.hpp"

namespace quad::planning {

struct Replan {
  PlanResult result;                      ///< the search's status, cells, cost and expansions
  std::vector<Eigen::Vector3d> waypoints;  ///< the shortcut path from the vehicle; empty unless kOk
  double known_free = 0.0;                ///< [m] of it the follower may fly
  /// [m] of arc length where it leaves known-free space, or the horizon ends short of its
  /// end; none when all of it may be flown.
  std::optional<double> frontier;
};

/// Plans from `from` (where the vehicle will be when the path takes effect) to the planner's
/// goal. A `from` outside the lattice plans from its nearest cell (below the ground clearance
/// taking off, between the geofence and its margin); one inside an inflated margin, from the
/// nearest free cell within the vehicle's diameter and a cell; one inside another vehicle's
/// tube (the planner's keep-out), from the nearest cell out of it within `keep_out_clearance`
/// and a cell. The path starts at `from`, by way of the search's first cell when that is
/// not `from`'s own (a straight line from the ground to the goal would skim the ground).
Replan replanFrom(DStarLite& planner, const Eigen::Vector3d& from, const PlanningParams& params,
                  double keep_out_clearance = 0.0);

/// Where `r` stops: the point at its frontier; none when all of it may be flown.
std::optional<Eigen::Vector3d> frontierPoint(const Replan& r);

/// Whether `next` is a new path for the follower against `previous`: another status, another
/// number of waypoints, a waypoint (the first, where the vehicle is expected, included) or the
/// stopping point (frontierPoint) moved by more than `resolution`.
bool changedPath(const Replan& next, const Replan& previous, double resolution);

}  // namespace quad::planning
