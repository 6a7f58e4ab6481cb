// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// From a path (a polyline) to a trajectory a quadrotor can fly, ending at rest at the path's
/// end.
///
/// - The path's corners are rounded within `corner_deviation` (curve.hpp).
/// - A speed profile along that curve starts at the start's speed, keeps each point's speed
///   within the limit and, in curves, within the lateral share of the acceleration limit,
///   changes speed at a share of the acceleration limit and ends at rest (forward and backward
///   passes). Its time law, smoothed over a window so that its acceleration ramps at half the
///   jerk limit, gives points of the curve at equal times (a fifth of a second apart), and the
///   minimum-snap spline (min_snap.hpp) passes them, from the start's full state. A moving
///   start is left free for its first half second: the path has neither its heading nor its
///   curvature, and the spline turns from one to the other as smoothly as it can.
/// - The spline is sampled. Where a piece breaks a limit (speed, acceleration, jerk, thrust,
///   tilt) or strays farther than `corridor` from the path, the profile is lowered over the part
///   of the curve it covers (the speed, where the excess is speed or across the motion; the
///   acceleration, where it is along it), and the spline solved again, until every sample keeps
///   every limit, or the trajectory is found infeasible.
/// - Every trajectory ends at rest: flown to its end, it stops there. A caller that only hands
///   it space known to be free has a stop in reach at every instant (FASTER's rule: Tordesillas
///   et al., "FASTER: Fast and safe trajectory planner for navigation in unknown
///   environments", IROS 2019), and the trajectory flown so far is the backup when a new one
///   fails.

#include <string>
#include <string_view>
#include <vector>

#include "quad/trajectory/trajectory.hpp"

namespace quad::trajectory {

/// What the vehicle may be asked to do.
struct Limits {
  double max_speed = 2.0;         ///< [m/s]
  double max_acceleration = 2.0;  ///< [m/s²] of the trajectory (not counting gravity)
  double max_jerk = 8.0;          ///< [m/s³]
  double max_tilt = 0.6;          ///< [rad] of the thrust (a + g ẑ) from the vertical
  double max_thrust = 15.0;       ///< [m/s²] ‖a + g ẑ‖: thrust over mass, less a margin for feedback
  double min_thrust = 3.0;        ///< [m/s²] ‖a + g ẑ‖ at least: never near free fall
  double gravity = 9.81;          ///< [m/s²]
};

struct GeneratorConfig {
  Limits limits;
  double corridor = 0.2;          ///< [m] the trajectory keeps this close to the path
  double corner_deviation = 0.1;  ///< [m] a corner's blend passes this far from it at most (≤ corridor)
  int max_iterations = 40;        ///< solves before a path is found infeasible
  int samples_per_piece = 12;     ///< where each piece's limits are checked
};

/// The largest values along a trajectory, sampled.
struct Extremes {
  double speed = 0.0;         ///< [m/s]
  double acceleration = 0.0;  ///< [m/s²]
  double jerk = 0.0;          ///< [m/s³]
  double tilt = 0.0;          ///< [rad]
  double max_thrust = 0.0;    ///< [m/s²]
  double min_thrust = 0.0;    ///< [m/s²] the smallest
};

/// The extremes of `trajectory`, `samples_per_piece` samples a piece and its ends.
Extremes extremes(const Trajectory& trajectory, double gravity = 9.81, int samples_per_piece = 32);

enum class GenerateStatus {
  kOk,
  kInvalidInput,  ///< a point or the start not finite, no point
  kInfeasible,    ///< limits or corridor still broken after every iteration
};

std::string_view toString(GenerateStatus status);

struct GenerateResult {
  GenerateStatus status = GenerateStatus::kInvalidInput;
  Trajectory trajectory;  ///< empty unless kOk
  int iterations = 0;     ///< spline solves
  std::string why;        ///< what was still broken, when not kOk
};

class Generator {
public:
  /// Throws std::invalid_argument naming the value when a limit is not positive and finite,
  /// the thrust limits do not bracket the weight, the corner deviation exceeds the corridor, or
  /// the iteration or sample counts are below 1.
  explicit Generator(GeneratorConfig config);

  /// A trajectory from `start` at sim time `t0` [s] along `path` to rest at its last point. The
  /// path's first point is where the trajectory starts: `start.p` is put in front of it when it
  /// is not that point. It stays within the corridor of the path, or of any of `also_free` (space
  /// the caller knows is free as well, such as the trajectory flown so far).
  GenerateResult generate(double t0, const State& start, const std::vector<Vector3>& path,
                          const std::vector<std::vector<Vector3>>& also_free = {}) const;

  /// Braking to rest from `current` at sim time `t` [s], as soon as the limits allow, along
  /// the curve `current` would have flown. When even its whole remaining curve is too short to
  /// brake on within the limits, `current` itself from `t` on (it ends at rest).
  GenerateResult stop(const Trajectory& current, double t) const;

  const GeneratorConfig& config() const { return config_; }

private:
  GeneratorConfig config_;
};

}  // namespace quad::trajectory
