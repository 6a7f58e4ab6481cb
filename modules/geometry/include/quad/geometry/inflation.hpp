// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The C-space obstacle of a spherical vehicle: an occupied voxel blocks every cell whose
/// centre is within the vehicle radius of the voxel's box (the Minkowski sum of the box and
/// a ball). Planning the centre's path among blocked cells keeps the whole sphere clear of
/// occupied boxes.

#include <vector>

#include "quad/geometry/grid.hpp"

namespace quad::geometry {

/// The offsets d (in voxels) of the cells blocked by an occupied voxel: those whose centre
/// lies within `radius` [m] of the box of the voxel at offset 0, i.e.
/// res · ‖max(|d| − ½, 0)‖ ≤ radius (ties included despite rounding). Sorted by distance, offset 0 first. Throws
/// std::invalid_argument for a negative or non-finite radius.
std::vector<VoxelIndex> inflationOffsets(double radius, double resolution);

/// Distance [m] from a cell's centre at voxel offset d to the box of the voxel at offset 0.
double centreToBoxDistance(const VoxelIndex& offset, double resolution);

}  // namespace quad::geometry
