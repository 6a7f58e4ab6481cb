// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Real scans as solid worlds: an OctoMap (`.bt`, `.ot`; Hornung et al. 2013) or a point
/// cloud (`.ply`, `.pcd`) placed with a pose and voxelised at a stated resolution.
///
/// - OctoMap: the leaves OctoMap calls occupied (occupancy above the tree's threshold, 0.5 by
///   default) are solid; free and unknown space are both open, since the simulator cannot
///   know what the scanner did not see. A leaf coarser than the resolution fills every voxel
///   it covers.
/// - Point cloud: every voxel holding a point is solid.
/// - Each occupied box (a leaf, or a point's voxel at the file's resolution) is sampled at
///   spacing ≤ resolution (≤ resolution / 2 when the pose turns it) and each sample, moved by
///   the pose, fills the world voxel it falls in. Unturned, with a translation on the voxel
///   grid and the map's own resolution, this is the identity on voxels.

#include <filesystem>
#include <stdexcept>

#include "quad/world/voxel_map.hpp"

namespace quad::world {

/// Where a scan lies in the world and how finely it is voxelised.
struct ScanPlacement {
  Vector3 position = Vector3::Zero();  ///< [m] world position of the scan's origin
  double yaw = 0.0;                    ///< [rad] about world z
  double resolution = 0.0;             ///< [m] 0: the OctoMap's own (required for point clouds)
};

/// A scan that cannot be used: the message names the file and why.
class ScanError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The scan's occupied voxels in the world. Throws ScanError for an unreadable or malformed
/// file, an octree that is not an OcTree, a point cloud without a resolution, or a scan with
/// nothing occupied.
VoxelMap loadScan(const std::filesystem::path& file, const ScanPlacement& placement);

}  // namespace quad::world
