// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Shortening a lattice path by line of sight through the planner's inflated grid.

#include <vector>

#include "quad/planning/dstar_lite.hpp"

namespace quad::planning {

/// True when the straight segment between two points [m] crosses only traversable cells
/// (sampled at a quarter of the resolution, so it never cuts the corner of a blocked cell).
bool lineOfSight(const DStarLite& planner, const Vector3& a, const Vector3& b);

/// The lattice path as waypoints [m] (cell centres), with every waypoint dropped that the
/// previous kept one can see past: greedy, start and goal kept.
std::vector<Vector3> shortcut(const DStarLite& planner, const std::vector<Cell>& cells);

}  // namespace quad::planning
