// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Distances between rotations: the guide's (eqs. 5, 6, 15, 16) and the geodesic angle.
///
/// For rotations that differ by an angle θ ∈ [0, π] (the angle of R₁ᵀR₂):
///   ρ(h₁, h₂)          = θ / 2            (eq. 6: the angle between ±h on S³, in [0, π/2])
///   ρ_s(h₁, h₂)        = θ / 2 or π − θ/2 (eq. 5: depends on which of ±h₂ is given)
///   ‖R₁ − R₂‖_F        = 2√2 sin(θ / 2)   (eq. 16, in [0, 2√2])
///   geodesicAngle(R₁, R₂) = θ             (the Riemannian distance on SO(3))
/// ρ, the Frobenius distance and θ are metrics on SO(3) and monotone in each other. The
/// Euclidean distance in yaw–pitch–roll (eq. 15) is a metric on the angle triples, not on
/// rotations: it is not invariant, and at gimbal lock one rotation has many triples.

#include "quad/geometry/quaternion.hpp"
#include "quad/geometry/so3.hpp"

namespace quad::geometry {

/// Eq. (5): arccos(h₁ · h₂) of the normalized quaternions, in [0, π].
double rhoS(const Quaternion& h1, const Quaternion& h2);

/// Eq. (6): min(ρ_s(h₁, h₂), ρ_s(h₁, −h₂)) = arccos|h₁ · h₂|, in [0, π/2].
double rho(const Quaternion& h1, const Quaternion& h2);

/// Eq. (15) with each angle difference wrapped to (−π, π], so that yaw 179° and −179° are 2°
/// apart rather than 358°.
double yprDistance(const YawPitchRoll& a, const YawPitchRoll& b);

/// Eq. (16): Euclidean distance in R⁹ between the matrices.
double frobeniusDistance(const Matrix3& R1, const Matrix3& R2);

/// The rotation angle of R₁ᵀR₂, in [0, π], accurate near 0 and π.
double geodesicAngle(const Matrix3& R1, const Matrix3& R2);
double geodesicAngle(const Quaternion& q1, const Quaternion& q2);

}  // namespace quad::geometry
