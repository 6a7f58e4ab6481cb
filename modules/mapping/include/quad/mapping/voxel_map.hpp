// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Voxels by their classification: the change sets the mapper sends, their order, and a
/// consumer's copy of the map (the planner's).

#include <cstdint>
#include <vector>

#include "quad/geometry/grid.hpp"
#include "quad/geometry/voxel_table.hpp"

namespace quad::mapping {

using geometry::VoxelIndex;

enum class VoxelState : std::uint8_t { kUnknown, kFree, kOccupied };

struct VoxelChange {
  VoxelIndex index;
  VoxelState state;  ///< after the change
};

/// Orders voxel indices x, then y, then z (for sorted change sets).
inline bool indexLess(const VoxelIndex& a, const VoxelIndex& b)
{
  if (a.x() != b.x()) {
    return a.x() < b.x();
  }
  return a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
}

/// Sorts by index (indexLess); equal indices keep no particular order.
void sortByIndex(std::vector<VoxelChange>& voxels);

/// A consumer's copy of the classification (the planner's): a snapshot, then change sets
/// applied in order, reproduce the mapper's classification exactly. Held in one flat table
/// (geometry::VoxelTable): a planner catching up copies a million voxels while its vehicle
/// hovers. Voxels farther than 2^19 from the origin on an axis (OctoMap's reach is 2^15)
/// cannot be in a map and are not held.
class VoxelMap {
public:
  explicit VoxelMap(double resolution) : resolution_(resolution) {}

  /// Replaces the contents with a snapshot's classification; false when the bytes are not an
  /// OctoMap binary tree of this resolution.
  bool applySnapshot(const std::vector<std::uint8_t>& bytes);
  void apply(const std::vector<VoxelChange>& changes);
  VoxelState classify(const VoxelIndex& index) const;
  std::size_t known() const { return voxels_.size(); }

  /// Every known voxel, sorted by index.
  std::vector<VoxelChange> contents() const;

private:
  double resolution_;
  geometry::VoxelTable voxels_;  // each voxel's VoxelState
};

}  // namespace quad::mapping
