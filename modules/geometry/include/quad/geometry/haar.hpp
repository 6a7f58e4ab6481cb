// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The Haar measure on SO(3): uniformly random rotations, and what their angles look like.
///
/// Shoemake, "Uniform random rotations", Graphics Gems III (1992): three uniform numbers in
/// [0, 1) give a point uniform on S³, hence (as ±q are identified) a Haar-uniform rotation.
/// Under the Haar measure the rotation angle θ ∈ [0, π] has density (1 − cos θ)/π and CDF
/// (θ − sin θ)/π: small angles are rare, as the volume of a ball of radius θ/2 on S³ is small.

#include <functional>
#include <random>
#include <vector>

#include "quad/geometry/quaternion.hpp"

namespace quad::geometry {

/// A Haar-uniform unit quaternion (canonical sign) drawn from `rng`.
Quaternion uniformRotation(std::mt19937_64& rng);

/// `count` uniform rotations from a generator seeded with `seed`: reproducible.
std::vector<Quaternion> uniformRotations(std::size_t count, std::uint64_t seed);

/// Density and CDF of the rotation angle under the Haar measure, for θ in [0, π].
double haarAngleDensity(double theta);
double haarAngleCdf(double theta);

/// The Kolmogorov–Smirnov statistic sup |F_n(x) − F(x)| of `samples` against `cdf`.
double kolmogorovSmirnov(std::vector<double> samples, const std::function<double(double)>& cdf);

}  // namespace quad::geometry
