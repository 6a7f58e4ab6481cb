// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plan/known_map.hpp"

#include <algorithm>
#include <cmath>

#include "quad/common/yaml_input.hpp"
#include "quad/geometry/polyline.hpp"
#include "quad/planning/shortcut.hpp"
#include "quad/world/world_file.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace quad::plan {

namespace {

using geometry::VoxelIndex;

/// The centres [m] of the lattice's first and last cells: the box its cells fill.
std::pair<Vector3, Vector3> cellCentreRange(const planning::Lattice& lattice)
{
  return {lattice.grid().centre(lattice.origin()),
          lattice.grid().centre(lattice.origin() + lattice.dims() - VoxelIndex::Ones())};
}

/// Marks the surface voxels of every obstacle, and every voxel a scan's voxel overlaps,
/// occupied (those that can block a cell of the lattice: within `inflation` [m] of it);
/// returns how many.
std::size_t giveObstacles(const world::World& world, planning::DStarLite& planner, double inflation)
{
  const planning::Lattice& lattice = planner.lattice();
  const geometry::VoxelGrid& grid = lattice.grid();
  const double half_diagonal = 0.5 * std::sqrt(3.0) * grid.resolution();
  const Vector3 reach = Vector3::Constant(inflation + grid.resolution());
  const auto [first, last] = cellCentreRange(lattice);
  const Vector3 region_lo = first - reach;
  const Vector3 region_hi = last + reach;
  std::size_t marked = 0;
  // Marks the voxels of the box [lo, hi] (clipped to the region that can block the lattice)
  // that `solid` says are occupied.
  const auto markBox = [&](Vector3 lo, Vector3 hi, const auto& solid) {
    lo = lo.cwiseMax(region_lo);
    hi = hi.cwiseMin(region_hi);
    if ((lo.array() > hi.array()).any()) {
      return;  // too far from the lattice to block any of it
    }
    const VoxelIndex a = grid.toIndex(lo);
    const VoxelIndex b = grid.toIndex(hi);
    for (int z = a.z(); z <= b.z(); ++z) {
      for (int y = a.y(); y <= b.y(); ++y) {
        for (int x = a.x(); x <= b.x(); ++x) {
          const VoxelIndex v(x, y, z);
          if (solid(v) && planner.voxelState(v) != planning::Occupancy::kOccupied) {
            planner.updateVoxel(v, planning::Occupancy::kOccupied);
            ++marked;
          }
        }
      }
    }
  };
  for (const world::Obstacle& o : world.obstacles()) {
    Vector3 lo;
    Vector3 hi;
    o.bounds(lo, hi);
    markBox(lo - Vector3::Constant(half_diagonal), hi + Vector3::Constant(half_diagonal),
            [&](const VoxelIndex& v) { return std::abs(o.signedDistance(grid.centre(v))) <= half_diagonal; });
  }
  // A scan's voxel makes every lattice voxel it overlaps occupied: what a mapper at the
  // lattice's resolution would see of it.
  for (const world::VoxelMap& m : world.maps()) {
    const Vector3 shrink = Vector3::Constant(1e-9 * m.resolution());  // its upper faces belong to the next voxels
    for (const VoxelIndex& v : m.occupiedVoxels()) {
      markBox(v.cast<double>() * m.resolution(), (v + VoxelIndex::Ones()).cast<double>() * m.resolution() - shrink,
              [](const VoxelIndex&) { return true; });
    }
  }
  return marked;
}

}  // namespace

PlanningSetup loadPlanningSetup(const std::filesystem::path& config, const std::vector<common::ParamOverride>& overrides)
{
  const common::Params p = config.empty() ? common::defaultParams(planning::planningSchema())
                                          : common::parseParams(common::readTextFile(config), config.string(),
                                                                planning::planningSchema(), overrides);
  planning::PlanningParams params = planning::planningParamsOf(p);
  world::World world = world::loadWorld(params.world_file);
  planning::fitToWorld(params, world.bounds().min, world.bounds().max, vehicle::loadVehicle(params.vehicle_file).radius,
                       p.origin());
  return {params.world_file, std::move(world), std::move(params)};
}

KnownMapPlan planOnKnownMap(const world::World& world, const planning::PlanningParams& params, bool land)
{
  planning::DStarLite planner(
      planning::Lattice(geometry::VoxelGrid(params.resolution), params.bounds_min, params.bounds_max), params.planner);
  KnownMapPlan out;
  out.occupied_voxels = giveObstacles(world, planner, params.planner.vehicle_radius);
  // Take-off: straight up from the start into the lattice's lowest layer (or down into its top).
  const auto [first, last] = cellCentreRange(planner.lattice());
  out.from = world.start();
  out.from.z() = std::clamp(out.from.z(), first.z(), last.z());
  // A start on a platform or beside a wall lies in their inflation: the take-off climbs
  // straight up until it leaves it.
  const double step = planner.lattice().grid().resolution();
  for (auto cell = planner.lattice().cellAt(out.from); cell && !planner.traversable(*cell) && out.from.z() + step <= last.z() + 1e-9;
       cell = planner.lattice().cellAt(out.from)) {
    out.from.z() += step;
  }
  out.climb_m = (out.from - world.start()).norm();
  // down to what lies beneath the goal: the ground, a roof, an upper floor
  out.landing_m = land ? std::max(0.0, world.goal().z() - world.supportHeight(world.goal(), params.planner.vehicle_radius)) : 0.0;
  const auto start = planner.lattice().cellAt(out.from);
  const auto goal = planner.lattice().cellAt(world.goal());
  if (!start || !goal) {
    out.status = planning::PlanStatus::kOutOfBounds;
    return out;
  }
  planner.setGoal(*goal);
  planner.setStart(*start);
  const planning::PlanResult r = planner.plan();
  out.status = r.status;
  out.expansions = r.expansions;
  if (r.status != planning::PlanStatus::kOk) {
    return out;
  }
  out.waypoints = planning::shortcut(planner, r.cells);
  out.waypoints.front() = out.from;
  out.waypoints.back() = world.goal();
  out.path_m = geometry::polylineLength(out.waypoints);
  out.optimum_m = out.climb_m + out.path_m + out.landing_m;
  return out;
}

}  // namespace quad::plan
