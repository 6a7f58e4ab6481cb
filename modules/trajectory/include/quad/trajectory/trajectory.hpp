// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A trajectory in time: pieces of degree-7 polynomials per axis, one after another, each in
/// its own normalised time. What the controller tracks: position, and velocity, acceleration
/// and jerk as feed-forward (a quadrotor is differentially flat in position and yaw: Mellinger
/// & Kumar, "Minimum snap trajectory generation and control for quadrotors", ICRA 2011).

#include <Eigen/Core>

#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::trajectory {

using geometry::Vector3;

/// Position and its first three derivatives at one instant, world frame.
struct State {
  Vector3 p = Vector3::Zero();  ///< [m]
  Vector3 v = Vector3::Zero();  ///< [m/s]
  Vector3 a = Vector3::Zero();  ///< [m/s²]
  Vector3 j = Vector3::Zero();  ///< [m/s³]
};

/// Coefficients per piece and axis: degree 7.
inline constexpr int kCoefficients = 8;
using Coefficients = Eigen::Matrix<double, 3, kCoefficients>;

/// One piece: p(τ) = Σₖ cₖ τᵏ with τ = (t − start) / duration in [0, 1]; each column a power
/// of τ, each row an axis. Normalised time keeps the coefficients in metres whatever the
/// duration, so pieces of milliseconds and of seconds solve alike.
struct Piece {
  double duration = 0.0;  ///< [s], positive
  Coefficients c = Coefficients::Zero();  ///< [m]

  /// The state `t` [s] after the piece's start (t is clamped to [0, duration]).
  State at(double t) const;
  /// [m/s⁴] the fourth derivative at `t` [s] after the start (clamped likewise).
  Vector3 snap(double t) const;
};

class Trajectory {
public:
  /// An empty trajectory: no piece, nothing to fly.
  Trajectory() = default;
  /// The pieces from `start_time` [s] on. Throws std::invalid_argument when there is none, a
  /// duration is not positive and finite, a coefficient or the start time is not finite.
  Trajectory(double start_time, std::vector<Piece> pieces);

  bool empty() const { return pieces_.empty(); }
  double startTime() const { return start_; }
  double endTime() const { return ends_.empty() ? start_ : ends_.back(); }
  double duration() const { return endTime() - start_; }
  const std::vector<Piece>& pieces() const { return pieces_; }

  /// The state at sim time `t` [s]: before the start, the start's position with the start's
  /// derivatives; after the end, the end's position at rest. An empty trajectory gives a
  /// zero state.
  State at(double t) const;
  /// [m] the length of the curve from time `from` to `to` [s] (within the trajectory).
  double length(double from, double to) const;

private:
  /// The piece at sim time t (the first or last outside the trajectory) and t from its start.
  std::pair<std::size_t, double> locate(double t) const;

  double start_ = 0.0;
  std::vector<Piece> pieces_;
  std::vector<double> ends_;  ///< [s] sim time at the end of each piece
};

/// A trajectory at rest at `p` [m] from `start_time` [s] for `duration` [s].
Trajectory restingAt(const Vector3& p, double start_time, double duration = 1.0);

}  // namespace quad::trajectory
