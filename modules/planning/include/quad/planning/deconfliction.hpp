// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Deconfliction of a fleet's vehicles, by priority: the vehicle of the lower id has the way.
/// Each planner keeps its vehicle out of a tube around every vehicle it yields to: the cells
/// whose centres lie within the clearance (both vehicles' radii, the separation, and the
/// safety margin the planner keeps from obstacles for the follower's deviation) of the
/// first `lookahead` metres of that vehicle's newest path. A path starts where its vehicle was
/// when its planner published it and goes where it will fly next, so the tube covers the
/// vehicle from then until it has flown the lookahead. A path older than `path_timeout` (its
/// planner stopped) is no longer kept out of: that vehicle is then seen only as the mapper sees
/// it, through the depth camera. The vehicle of the higher id does all the yielding; the other
/// flies on as if alone. A path takes effect kPathEffectDelayNs of sim time after its stamp,
/// whenever it arrives within that time: in lockstep the replans that follow it, and so the
/// runs, repeat.

#include <cstdint>
#include <map>
#include <vector>

#include "quad/planning/dstar_lite.hpp"

namespace quad::planning {

struct FleetRule {
  double separation = 1.0;      ///< [m] kept between two vehicles' bounding spheres
  double lookahead = 4.0;       ///< [m] of the other's path kept out of, from its first point
  double path_timeout_s = 2.0;  ///< [s] of sim time a path is kept out of after its stamp
};

/// [ns] of sim time after its stamp that another vehicle's path takes effect.
inline constexpr std::int64_t kPathEffectDelayNs = 100'000'000;

/// Whether vehicle `self` gives way to vehicle `other`: the lower id has the way.
constexpr bool yieldsTo(std::uint32_t self, std::uint32_t other) { return other < self; }

/// The lattice's cells whose centres lie within `clearance` [m] of the first `lookahead` [m]
/// of `path` (its only point when it has one; nothing when it is empty), sorted, no repeats.
std::vector<Cell> cellsNear(const Lattice& lattice, const std::vector<Vector3>& path, double lookahead,
                            double clearance);

/// One planner's view of the other vehicles: their newest paths, and the cells to keep out of.
class Deconfliction {
public:
  /// `self`: this vehicle's id; `inflation` [m]: its planner's obstacle inflation (its radius
  /// and safety margin); `radius` [m]: its bounding sphere, taken for the others' too (a
  /// fleet's vehicles are alike).
  Deconfliction(std::uint32_t self, FleetRule rule, double inflation, double radius);

  /// Vehicle `vehicle`'s path as its planner published it at sim time `stamp_ns`. This
  /// vehicle's own, those of vehicles it has the way over and ones not newer than the newest
  /// heard are ignored.
  void onPath(std::uint32_t vehicle, std::int64_t stamp_ns, std::vector<Vector3> waypoints);
  /// The vehicles whose tubes are kept out of at sim time `now_ns`: each one's newest path in
  /// effect then (stamped kPathEffectDelayNs or more before), if it is no older than the
  /// timeout and has at least one point.
  std::vector<std::uint32_t> yieldingTo(std::int64_t now_ns) const;
  /// Their tubes' cells, sorted, no repeats.
  std::vector<Cell> keepOut(const Lattice& lattice, std::int64_t now_ns) const;
  /// [m] Between a cell centre of this vehicle's and another vehicle's path: the inflation,
  /// the other's radius and the separation.
  double clearance() const { return inflation_ + radius_ + rule_.separation; }
  const FleetRule& rule() const { return rule_; }

private:
  struct Heard {
    std::int64_t stamp_ns = 0;
    std::vector<Vector3> waypoints;
  };
  /// A vehicle's path in effect at now_ns; null when none is.
  const Heard* inEffect(const std::vector<Heard>& heard, std::int64_t now_ns) const;

  std::uint32_t self_;
  FleetRule rule_;
  double inflation_;
  double radius_;
  std::map<std::uint32_t, std::vector<Heard>> paths_;  // per vehicle, oldest first
};

}  // namespace quad::planning
