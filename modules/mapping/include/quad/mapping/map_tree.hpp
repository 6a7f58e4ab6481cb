// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The mapper's octree: an octomap::OcTree whose point-cloud insertion builds exactly the tree
/// `OcTree::insertPointCloud` builds (not discretized, inner nodes kept up to date), and on
/// the way reports every voxel whose classification changed.
///
/// OctoMap's own route costs two descents per voxel (a search for its early abort at the
/// clamping bounds, then the update), keeps its key sets in node-allocating hash sets, and
/// its change detection adds a hash-map insertion for every new voxel. Here the keys of a
/// scan go into one flat open-addressing set, and each voxel is updated by one descent that
/// does the early abort, the update and the change check together, then one ascent that
/// prunes or refreshes the inner nodes, as OctoMap's recursion does.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <octomap/OcTree.h>

namespace quad::mapping {

/// A voxel whose classification a scan changed, by its OctoMap key.
struct KeyChange {
  octomap::OcTreeKey key;
  bool occupied;  ///< after the scan (it is known after, by construction)
};

/// The set of keys one scan touches: free along the rays, occupied at the endpoints, with
/// an occupied endpoint winning over a ray that crosses the same voxel (OctoMap's rule).
class ScanKeySet {
public:
  void clear();
  void insertFree(const octomap::OcTreeKey& key) { insert(pack(key), 0); }
  void insertOccupied(const octomap::OcTreeKey& key) { insert(pack(key), kOccupiedBit); }
  std::size_t size() const { return order_.size(); }

  /// Calls f(key, occupied) once per key, in first-insertion order.
  template <typename F>
  void forEach(F&& f) const
  {
    for (const std::uint32_t slot : order_) {
      const std::uint64_t v = slots_[slot];
      f(unpack(v), (v & kOccupiedBit) != 0);
    }
  }

private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  static constexpr std::uint64_t kOccupiedBit = std::uint64_t{1} << 63;
  static constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << 48) - 1;

  static std::uint64_t pack(const octomap::OcTreeKey& k)
  {
    return std::uint64_t{k[0]} | (std::uint64_t{k[1]} << 16) | (std::uint64_t{k[2]} << 32);
  }
  static octomap::OcTreeKey unpack(std::uint64_t v)
  {
    return {static_cast<octomap::key_type>(v & 0xffff), static_cast<octomap::key_type>((v >> 16) & 0xffff),
            static_cast<octomap::key_type>((v >> 32) & 0xffff)};
  }
  void insert(std::uint64_t key, std::uint64_t flag);
  void grow();

  std::vector<std::uint64_t> slots_;   // key | flag, or kEmpty
  std::vector<std::uint32_t> order_;   // occupied slots, in insertion order
  int shift_ = 64;                     // 64 − log2(capacity)
};

class MapTree : public octomap::OcTree {
public:
  explicit MapTree(double voxel_size) : octomap::OcTree(voxel_size) {}

  /// OcTree::insertPointCloud(cloud, origin, max_range) (lazy_eval off, not discretized),
  /// with the voxels whose classification changed appended to `changes`, each once.
  void insertPointCloudTracked(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range,
                               std::vector<KeyChange>& changes);

  /// Only voxels whose keys lie in [lo, hi] (inclusive, per axis) are updated from now on, as
  /// OctoMap's bounding-box limit does: rays still run their whole length, what they cross
  /// outside the box is left alone.
  void limitTo(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi)
  {
    box_lo_ = lo;
    box_hi_ = hi;
    limited_ = true;
  }

private:
  bool inBox(const octomap::OcTreeKey& k) const
  {
    return !limited_ || (k[0] >= box_lo_[0] && k[0] <= box_hi_[0] && k[1] >= box_lo_[1] && k[1] <= box_hi_[1] &&
                         k[2] >= box_lo_[2] && k[2] <= box_hi_[2]);
  }
  /// OcTree::updateNode(key, occupied) in one descent; the voxel's classification after it
  /// (true: occupied) when that changed, nothing when it did not. The descent starts where
  /// the previous update's path and this key's part (a ray's voxels come one after another).
  std::optional<bool> updateTracked(const octomap::OcTreeKey& key, bool occupied);

  ScanKeySet keys_;
  // The last update's path from the root: path_[0 ... path_valid_] still exist as they were
  // (-1: none, as at the start of a scan; the tree may have changed since the last one).
  std::array<octomap::OcTreeNode*, 17> path_{};
  octomap::OcTreeKey path_key_;
  int path_valid_ = -1;
  octomap::KeyRay ray_;
  bool limited_ = false;  // updates only inside [box_lo_, box_hi_]
  octomap::OcTreeKey box_lo_;
  octomap::OcTreeKey box_hi_;
};

}  // namespace quad::mapping
