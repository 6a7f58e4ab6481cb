// SPDX-License-Identifier: BSD-3-Clause
#include "quad/planning/replan.hpp"

#include <algorithm>

#include "quad/geometry/polyline.hpp"
#include "quad/planning/known_space.hpp"
#include "quad/planning/shortcut.hpp"

namespace quad::planning {

using Eigen::Vector3d;

Replan replanFrom(DStarLite& planner, const Vector3d& from, const PlanningParams& params, double keep_out_clearance)
{
  std::optional<Cell> start;
  if (from.allFinite()) {
    start = planner.lattice().nearestCell(from);
  }
  if (start && !planner.traversable(*start)) {
    // Drifted into an inflated margin (or a cell just became blocked): leave it by the
    // nearest free cell rather than report the start blocked.
    start = planner.nearestTraversable(*start, 2.0 * params.planner.vehicle_radius + params.resolution).value_or(*start);
  }
  if (start && !planner.traversable(*start) && !planner.keepOut().empty()) {
    start = planner.nearestTraversable(*start, keep_out_clearance + params.resolution).value_or(*start);
  }
  Replan r;
  if (!start) {
    r.result.status = PlanStatus::kOutOfBounds;
    return r;
  }
  planner.setStart(*start);
  r.result = planner.plan(params.max_expansions);
  if (r.result.status == PlanStatus::kOk) {
    r.waypoints = shortcut(planner, r.result.cells);
    if ((r.waypoints.front() - from).norm() > params.resolution) {
      r.waypoints.insert(r.waypoints.begin(), from);
    } else {
      r.waypoints.front() = from;
    }
    if (params.known_space.horizon > 0.0) {
      r.frontier = knownFreeLength(planner, r.waypoints, from, params.known_space);
    }
  }
  // Up to the frontier, or up to the horizon when everything checked is known free (what lies
  // beyond was not looked at: FASTER's rule commits to none of it).
  const double length = geometry::polylineLength(r.waypoints);
  r.known_free = r.frontier                           ? *r.frontier
                 : params.known_space.horizon > 0.0 ? std::min(params.known_space.horizon, length)
                                                      : length;
  if (!r.frontier && r.known_free < length) {
    r.frontier = r.known_free;
  }
  return r;
}

std::optional<Vector3d> frontierPoint(const Replan& r)
{
  return r.frontier ? std::optional<Vector3d>(geometry::pointAlong(r.waypoints, *r.frontier)) : std::nullopt;
}

bool changedPath(const Replan& next, const Replan& previous, double resolution)
{
  if (next.result.status != previous.result.status || next.waypoints.size() != previous.waypoints.size()) {
    return true;
  }
  // The first point is where the vehicle is expected: a path that starts a voxel away from the
  // last one's start (a climb, a drift) is new, so that a follower taking it later (at the
  // mission's start) joins it where the vehicle is, not where it was.
  for (std::size_t i = 0; i < next.waypoints.size(); ++i) {
    if ((next.waypoints[i] - previous.waypoints[i]).norm() > resolution) {
      return true;
    }
  }
  const auto stop = frontierPoint(next);
  const auto stopped = frontierPoint(previous);
  return stop.has_value() != stopped.has_value() || (stop && (*stop - *stopped).norm() > resolution);
}

}  // namespace quad::planning
