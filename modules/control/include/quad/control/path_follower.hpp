// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// From a planned path (a polyline of waypoints) to a smooth, time-parameterised reference:
/// the guide's sim.createPath / sim.getPathLengths / sim.getSimulationTimeStep in our terms.
///
/// Corners are rounded with quadratic Bézier blends whose deviation from the polyline is at
/// most `corner_deviation` (so the curve stays inside a corridor the planner kept free by at
/// least that margin); an arc-length table samples the curve; a speed profile respects the
/// speed limit, the lateral acceleration in curves and the acceleration limit (forward and
/// backward passes, ending at rest); a jerk-limited time law follows that profile, braking for
/// the end by its jerk-limited stopping distance, creeping the last millimetres and stopping
/// on the end point from at most 5 cm/s. Each tick
/// samples position, velocity, acceleration and a rate-limited yaw facing along the path.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "quad/control/geometric_controller.hpp"

namespace quad::control {

struct FollowerLimits {
  double max_speed = 2.0;                 ///< [m/s]
  double max_acceleration = 2.0;          ///< [m/s²] along the path
  double max_jerk = 6.0;                  ///< [m/s³]
  double max_lateral_acceleration = 2.0;  ///< [m/s²] in curves
  double max_yaw_rate = 1.0;              ///< [rad/s]
  double corner_deviation = 0.1;          ///< [m] largest distance of the curve from the polyline
  /// [m/s²] the hardest braking, only when a path joined while moving turns back after its
  /// lead-in (never less than max_acceleration)
  double max_braking = 4.0;
  double sample_spacing = 0.05;           ///< [m] of the arc-length table
};

/// The smooth curve through the waypoints and its speed profile.
class Trajectory {
public:
  struct Point {
    Vector3 p = Vector3::Zero();
    Vector3 tangent = Vector3::UnitX();  ///< unit
    Vector3 normal = Vector3::Zero();    ///< unit towards the centre of curvature (0 when straight)
    double curvature = 0.0;              ///< [1/m]
    double speed_limit = 0.0;            ///< [m/s] from the speed profile
  };

  /// Consecutive duplicate waypoints are dropped. `start_speed` [m/s] is the speed at s = 0
  /// (joining a path while moving). Fewer than two distinct waypoints give a zero-length
  /// trajectory at the single point.
  Trajectory(std::vector<Vector3> waypoints, const FollowerLimits& limits, double start_speed = 0.0);

  double length() const { return length_; }
  /// The curve at arc length s (clamped to [0, length]), interpolated in the table.
  Point at(double s) const;
  /// The lowest speed limit of the profile over [from, to].
  double lowestSpeedLimit(double from, double to) const;
  /// The deceleration [m/s²] that brings speed `v` at arc length `s` down to the speed
  /// profile everywhere within `horizon` metres ahead (0 when it is already below it).
  double brakingNeeded(double s, double v, double horizon) const;
  const std::vector<Vector3>& waypoints() const { return waypoints_; }

private:
  /// Indices [first, last) of the table's samples with arc length in (from, to].
  std::pair<std::size_t, std::size_t> samplesWithin(double from, double to) const;

  std::vector<Vector3> waypoints_;
  std::vector<double> s_;
  std::vector<Point> table_;
  double length_ = 0.0;
};

class PathFollower {
public:
  explicit PathFollower(FollowerLimits limits);

  /// Starts following new waypoints. While moving, the new curve starts at the current
  /// reference (with a short lead-in along the current velocity) and keeps its speed, so the
  /// reference never jumps. Returns false (and keeps the old path) when a waypoint is
  /// non-finite or there are none.
  bool setPath(const std::vector<Vector3>& waypoints, std::uint32_t version);

  /// Holds position `p` (no path): what hover means.
  void hold(const Vector3& p, double yaw);

  /// Advances the time law by dt [s] and samples the reference.
  Reference step(double dt);

  const Reference& reference() const { return ref_; }
  bool finished() const;  ///< at the end of the path, at rest
  std::optional<std::uint32_t> version() const { return version_; }
  double progress() const { return s_; }
  const Trajectory* trajectory() const { return trajectory_ ? &*trajectory_ : nullptr; }
  const FollowerLimits& limits() const { return limits_; }

private:
  FollowerLimits limits_;
  std::optional<Trajectory> trajectory_;
  std::optional<std::uint32_t> version_;
  std::optional<Vector3> lead_in_;  // the lead-in point of the path joined last
  double turn_back_end_ = 0.0;      // [m] a metre past the turn of a path that turns back (0: none)
  double s_ = 0.0;
  double v_ = 0.0;
  double a_ = 0.0;
  Reference ref_;
};

}  // namespace quad::control
