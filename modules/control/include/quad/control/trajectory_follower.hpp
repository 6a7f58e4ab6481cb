// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What the controller flies: a trajectory in time (quad::trajectory), sampled each tick for
/// the reference and its feed-forward (velocity, acceleration, jerk), with a heading that faces
/// along the motion at a limited rate.
///
/// Each new path (a replan, a take-off, a way back) becomes a new trajectory from the
/// reference's full state at that moment (position, velocity, acceleration and jerk: nothing
/// jumps), along the path from where it passes nearest the reference, to rest at its end. The
/// trajectory flown so far is kept when no trajectory along a new path keeps the limits from
/// there: it ends at rest in space it was made for, so a stop is always in reach (FASTER's
/// rule, Tordesillas et al. 2019). Holding while moving brakes along the trajectory flown.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quad/control/geometric_controller.hpp"
#include "quad/trajectory/generator.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace quad::control {

struct FollowerLimits {
  double max_speed = 2.0;         ///< [m/s]
  double max_acceleration = 2.0;  ///< [m/s²] of the trajectory's feed-forward
  double max_jerk = 20.0;         ///< [m/s³]
  double max_yaw_rate = 1.0;      ///< [rad/s]
  double corner_deviation = 0.08;  ///< [m] a rounded corner passes at most this far from the path's corner
  /// [m] the trajectory keeps this close to the path (or to the trajectory it replaces): at most
  /// the planner's known_free.margin, which checks that much past the vehicle's radius
  double corridor = 0.1;
  /// [m/s²] the hardest braking when the follower must stop (a hold while moving): a failsafe
  /// may ask for more than a mission's acceleration (never less)
  double max_braking = 4.0;
  /// Shares of the vehicle's thrust and of the controller's tilt limit a trajectory may ask
  /// for: the rest is the feedback's (tracking errors, wind, a model that is off).
  double thrust_share = 0.8;
  double tilt_share = 0.8;
};

/// The generator's configuration for these limits, a vehicle (its top thrust over its mass)
/// and the controller's tilt limit `max_tilt` [rad].
trajectory::GeneratorConfig generatorConfig(const FollowerLimits& limits, const vehicle::VehicleParams& vehicle,
                                            double max_tilt, double gravity = 9.81);

class TrajectoryFollower {
public:
  /// Throws std::invalid_argument (the generator's) naming a limit out of its range.
  TrajectoryFollower(FollowerLimits limits, const trajectory::GeneratorConfig& generator);

  /// Flies `waypoints` from the reference at sim time `t` [s]. Within the corridor of the
  /// path, the reference goes straight on to the waypoint after the point nearest it (the
  /// trajectory keeps within the corridor of that hop: within twice the corridor of the path);
  /// farther off, or when no trajectory within the limits goes straight on, it joins the path
  /// at that nearest point. False, with the trajectory flown kept (lastRefusal() says why),
  /// when there is no waypoint, one is not finite, or no trajectory from the reference along
  /// them keeps the limits.
  bool setPath(const std::vector<Vector3>& waypoints, std::uint32_t version, double t);

  /// Holds position `p` with heading `yaw` [rad] from sim time `t` (no path): what hover
  /// means at rest.
  void hold(const Vector3& p, double yaw, double t);

  /// Brakes to rest from sim time `t` along the trajectory flown, as soon as the limits allow
  /// (its deceleration up to max_braking; at rest already: holds there). What hover means
  /// while moving.
  void brake(double t);

  /// The reference at sim time t [s].
  Reference step(double t);

  const Reference& reference() const { return ref_; }
  /// At rest at the end of the trajectory at sim time t.
  bool finished(double t) const;
  /// The path version the trajectory follows (none: a hold, a stop, the controller's own).
  std::optional<std::uint32_t> version() const { return version_; }
  /// [m] arc length flown along the trajectory since it was taken.
  double progress() const { return progress_; }
  const trajectory::Trajectory& trajectory() const { return trajectory_; }
  /// How many trajectories were taken so far: changes with each new one.
  std::uint32_t taken() const { return taken_; }
  /// Paths refused so far, and why the last was.
  std::uint64_t refused() const { return refused_; }
  const std::string& lastRefusal() const { return last_refusal_; }
  const FollowerLimits& limits() const { return limits_; }

private:
  void take(trajectory::Trajectory next, std::optional<std::uint32_t> version, double t);

  FollowerLimits limits_;
  trajectory::Generator generator_;
  trajectory::Generator braking_;  // the same, braking at up to max_braking
  trajectory::Trajectory trajectory_;
  std::optional<std::uint32_t> version_;
  std::uint32_t taken_ = 0;
  std::uint64_t refused_ = 0;
  std::string last_refusal_;
  double progress_ = 0.0;
  double last_t_ = 0.0;
  Reference ref_;
};

}  // namespace quad::control
