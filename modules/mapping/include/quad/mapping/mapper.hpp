// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Probabilistic 3D occupancy mapping with OctoMap (Hornung et al., "OctoMap: an efficient
/// probabilistic 3D mapping framework based on octrees", Autonomous Robots 2013), and the
/// change sets an incremental planner needs: after each scan, exactly the voxels whose
/// classification (unknown, free, occupied) changed.
///
/// Voxels are OctoMap's leaves at the map resolution; their indices are quad::geometry's
/// (VoxelGrid: voxel i covers [i·res, (i+1)·res), OctoMap key = i + 32768).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <octomap/OcTree.h>

#include "quad/common/param_table.hpp"
#include "quad/geometry/grid.hpp"
#include "quad/mapping/map_tree.hpp"
#include "quad/mapping/tree_bytes.hpp"
#include "quad/mapping/voxel_map.hpp"

namespace quad::mapping {

using geometry::Vector3;

struct MapperConfig {
  double resolution = 0.2;           ///< [m] voxel edge
  double min_range = 0.0;            ///< [m] closer points are dropped
  double max_range = 20.0;           ///< [m] farther points only clear space (with the sensor's own)
  double prob_hit = 0.7;
  double prob_miss = 0.4;
  double clamp_min = 0.12;
  double clamp_max = 0.97;
  double occupancy_threshold = 0.5;
  std::optional<double> min_z;       ///< [m] points below are dropped
  std::optional<double> max_z;       ///< [m] points above are dropped
  std::size_t max_points = 65536;    ///< larger clouds are refused as absurd
  /// [m] The box the map covers (the world's: nothing flies outside it); voxels outside are
  /// never updated, so rays into the sky or past the walls cost no map. Unset: unbounded.
  std::optional<std::pair<Vector3, Vector3>> box;

  /// Limits the map to a world of bounds [min, max], one voxel beyond them (a wall on the
  /// bounds is mapped whole).
  void coverWorld(const Vector3& min, const Vector3& max)
  {
    const Vector3 margin = Vector3::Constant(resolution);
    box = std::make_pair(Vector3(min - margin), Vector3(max + margin));
  }
};

/// The mapper's parameters as configs/mapping.yaml writes them (its `map.*` keys):
/// MapperConfig's fields, and the height band as a switch with its limits.
struct MapperParams {
  MapperConfig map;
  bool height_limits = false;  ///< keep only points within [min_z, max_z]
  double min_z = -1.0;         ///< [m]
  double max_z = 50.0;         ///< [m]
};

/// Each `map.*` key with its unit, range and the field it fills; defaults are MapperParams'.
const common::ParamTable<MapperParams>& mapperTable();
/// The config they make, refusing contradictions (hit <= 0.5, clamp_min >= threshold, ...)
/// with `origin:key: value: reason`.
MapperConfig mapperConfigFrom(const MapperParams& params, const std::string& origin);
/// mapperTable()'s values of validated `params`, then the above.
MapperConfig mapperConfigFrom(const common::Params& params);

/// One depth scan in the world frame.
struct Scan {
  Vector3 origin_W = Vector3::Zero();  ///< [m] sensor origin
  std::vector<Vector3> points_W;       ///< [m] hits, and misses beyond max_range
  double max_range = 0.0;              ///< [m] the sensor's; 0: the mapper's only
};

struct IntegrationResult {
  bool accepted = false;
  std::string rejection;               ///< why not, when not accepted
  std::vector<VoxelChange> changes;    ///< sorted by index
  std::size_t points = 0;              ///< points integrated (after range and height limits)
};

class Mapper {
public:
  /// Throws std::invalid_argument on an inconsistent config (as mapperConfigFrom checks).
  explicit Mapper(MapperConfig config);

  /// Integrates a scan: free space along each ray from the origin, the endpoint occupied
  /// when within range; points beyond range only clear up to it. A scan with a non-finite
  /// origin or point, or more than max_points, is refused whole: nothing changes. In a
  /// bounded map (config.box) the changes come first and the octree's own update is left to
  /// settle(), which the readers of the tree below call first (MapTree::reportPointCloud);
  /// its images come from the box's voxels, without the tree (MapTree::voxelBox).
  IntegrationResult integrate(const Scan& scan);
  /// Brings the octree up to date with the scans integrated.
  void settle() const { settled(); }

  VoxelState classify(const VoxelIndex& index) const;
  /// Every known voxel with its state (pruned octree nodes expanded to the resolution).
  std::vector<VoxelChange> classification() const;

  /// The map as OctoMap's binary (.bt) bytes: maximum-likelihood free/occupied per voxel.
  std::vector<std::uint8_t> snapshot() const { return image(false).binary; }
  /// The snapshot, with the tree's node data (`with_data`) and its memory use, from one walk.
  TreeImage image(bool with_data) const;
  /// The same image of the map as the scans integrated so far left it, worked out on a thread
  /// of its own while more scans are integrated: a bounded map's voxels are copied for that
  /// thread (a few MB, in about a millisecond), and their image is the work there, each
  /// block of them unchanged since the last such image taken from it again. `done`
  /// (optional) is called once the image is worked out, on that thread, just before the
  /// future holds it (a caller it wakes that finds the future not yet ready looks again
  /// later). One image at a time: a second waits for the first. An unbounded map's image is
  /// worked out here, ready at once (`done` called here).
  std::shared_future<TreeImage> imageLater(bool with_data, std::function<void()> done = {});
  /// Writes a .bt file that OctoMap's own tools (octovis, binvox2bt ...) read; false on I/O failure.
  bool save(const std::filesystem::path& file) const;
  /// Replaces an empty tree with its node data (OctoMap's, as in its .ot files: every node's
  /// log-odds; treeDataBytes, image()); false (the tree left empty) when the bytes are cut
  /// short or the mapper already holds voxels.
  bool readTree(std::istream& in);

  std::size_t nodes() const { return image(false).nodes; }
  double resolution() const { return config_.resolution; }
  /// Updates dropped at a voxel's clamping bound without a descent (MapTree's figure).
  std::uint64_t updatesSkippedAtBounds() const { return tree_.updatesSkippedAtBounds(); }
  /// The octree, up to date with the scans integrated before this call (not those after).
  const MapTree& tree() const { return settled(); }

private:
  /// Waits for imageLater's image, if one is being worked out: the copy of the voxels is that
  /// thread's until then.
  void awaitImage() const
  {
    if (image_job_.valid()) {
      image_job_.wait();
    }
  }
  const MapTree& settled() const
  {
    tree_.settle();
    return tree_;
  }

  MapperConfig config_;
  // Mutable for settle(): the tree catching up with scans already integrated changes no
  // answer a reader gets.
  mutable MapTree tree_;
  geometry::VoxelGrid grid_;
  std::vector<std::uint32_t> image_words_;   // the voxels imageLater's thread works on
  std::vector<std::uint8_t> image_changed_;  // the blocks of them changed since its last image
  BoxImageCache image_cache_;                // that image's blocks
  std::shared_future<TreeImage> image_job_;  // imageLater's, the last (after image_words_: it goes first)
};

/// Every known voxel of an octree, expanded to its resolution, sorted.
std::vector<VoxelChange> classificationOf(const octomap::OcTree& tree);

/// The same of a snapshot's bytes; nothing when they are not an OctoMap binary tree of this
/// resolution.
std::optional<std::vector<VoxelChange>> classificationOf(const std::vector<std::uint8_t>& snapshot, double resolution);

/// The centres of a snapshot's occupied voxels [m], in classificationOf's order; nothing when
/// the bytes are not an OctoMap binary tree of this resolution.
std::optional<std::vector<geometry::Vector3>> occupiedCentres(const std::vector<std::uint8_t>& snapshot,
                                                              double resolution);

}  // namespace quad::mapping
