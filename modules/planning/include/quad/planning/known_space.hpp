// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// How far along a path the vehicle stays in space its sensors have seen free. The planner
/// is optimistic about unknown space (it plans through it, so it can plan over a wall it has
/// not yet seen the top of), and the follower is not: it flies only as fast as lets it stop
/// before the path leaves known-free space (the policy of Tordesillas et al., "FASTER: Fast
/// and Safe Trajectory Planner for Flights in Unknown Environments", IROS 2019: plan in
/// known and unknown space, commit only to the part in known-free space).

#include <optional>
#include <vector>

#include "quad/planning/dstar_lite.hpp"

namespace quad::planning {

struct KnownSpaceCheck {
  double radius = 0.2;        ///< [m] around the path's centre line, every voxel must be known free
  double own_radius = 0.55;   ///< [m] voxels this close to the vehicle count as free: it is there
  double horizon = 8.0;       ///< [m] of path checked; what lies beyond does not change the answer
};

/// The frontier: the arc length [m] from the first waypoint to where the polyline enters the
/// first voxel whose neighbourhood (the voxels within `check.radius` of its centre) holds a
/// voxel not known free (unknown or occupied). Nothing when there is none within
/// `check.horizon` of path. Voxels within `check.own_radius` of `vehicle_W` count as free, and
/// so do occupied voxels read round the voxel the vehicle is in (it is there already). The
/// polyline is walked voxel by voxel (Amanatides & Woo 1987), each voxel's neighbourhood read
/// once.
std::optional<double> knownFreeLength(const DStarLite& planner, const std::vector<Vector3>& waypoints,
                                      const Vector3& vehicle_W, const KnownSpaceCheck& check);

}  // namespace quad::planning
