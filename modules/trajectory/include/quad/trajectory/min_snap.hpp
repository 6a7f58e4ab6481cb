// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The minimum-snap spline through given points at given times: Mellinger & Kumar, "Minimum
/// snap trajectory generation and control for quadrotors" (ICRA 2011), in the unconstrained
/// form of Richter, Bry & Roy, "Polynomial trajectory planning for aggressive quadrotor flight
/// in dense indoor environments" (ISRR 2013).
///
/// Among curves that start in a given state (position, velocity, acceleration, jerk), pass the
/// interior points at the given times and end in a given state, the one that minimises
/// ∫‖p⁽⁴⁾‖² dt is, by its Euler–Lagrange equation p⁽⁸⁾ = 0, a polynomial of degree 7 on each
/// piece whose derivatives 1 to 6 are continuous at the interior points. Those conditions
/// make a square linear system of 8 equations a piece, solved here at once for the three axes
/// (they share its matrix).

#include <optional>
#include <vector>

#include "quad/trajectory/trajectory.hpp"

namespace quad::trajectory {

/// The pieces from `start` through `through` (one point between each two pieces) to `end`,
/// piece i lasting `durations[i]` [s]. nullopt when the sizes disagree (durations must be one
/// more than the points), a duration is not positive, an input is not finite, or the system
/// is singular.
std::optional<std::vector<Piece>> minimumSnap(const State& start, const std::vector<Vector3>& through,
                                              const State& end, const std::vector<double>& durations);

/// [m²/s⁷] ∫‖p⁽⁴⁾‖² dt over the pieces (Gauss–Legendre, exact for their degree).
double snapCost(const std::vector<Piece>& pieces);

}  // namespace quad::trajectory
