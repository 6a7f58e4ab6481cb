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
#include <cstdlib>
#include <memory>
#include <optional>
#include <vector>

#include <octomap/OcTree.h>

#include "quad/mapping/tree_bytes.hpp"

namespace quad::mapping {

/// A voxel whose classification a scan changed, by its OctoMap key.
struct KeyChange {
  octomap::OcTreeKey key;
  bool occupied;  ///< after the scan (it is known after, by construction)
};

/// The set of keys one scan touches: free along the rays, occupied at the endpoints, with
/// an occupied endpoint winning over a ray that crosses the same voxel (OctoMap's rule).
///
/// A scan's rays stay within their range of the sensor, so the keys within that range are
/// kept in a dense window around it, one bit a voxel (a ray's next voxel is a bit test, not a
/// hash probe into a table that spreads neighbours apart); keys outside it, or every key of a
/// scan whose range is too long for a window, go into a flat open-addressing set.
class ScanKeySet {
public:
  /// Empties the set; keys within `radius` of `centre` along every axis go into the window.
  /// Without a window (radius 0, or one wider than kMaxWindowRadius) every key is hashed.
  void clear(const octomap::OcTreeKey& centre, unsigned radius);
  void clear() { clear(octomap::OcTreeKey(0, 0, 0), 0); }
  void insertFree(const octomap::OcTreeKey& key) { insert(key, false); }
  void insertOccupied(const octomap::OcTreeKey& key) { insert(key, true); }
  std::size_t size() const { return order_.size(); }

  /// Calls f(key, occupied) once per key, in first-insertion order.
  template <typename F>
  void forEach(F&& f) const
  {
    for (const std::uint64_t v : order_) {
      const octomap::OcTreeKey key = unpack(v);
      const auto at = windowIndex(key);
      f(key, at ? test(occupied_, *at) : (slots_[find(v)] & kOccupiedBit) != 0);
    }
  }

  /// The widest window [voxels from the centre]: 2·128 + 1 a side, 2.1 MB for each of its
  /// two bitmaps. A 0.2 m map's window reaches 25 m.
  static constexpr unsigned kMaxWindowRadius = 128;

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
  static bool test(const std::vector<std::uint64_t>& bits, std::size_t i)
  {
    return ((bits[i >> 6] >> (i & 63)) & 1U) != 0;
  }

  /// The key's bit in the window, nothing outside it (or without one).
  std::optional<std::size_t> windowIndex(const octomap::OcTreeKey& k) const
  {
    const unsigned dx = static_cast<unsigned>(k[0] - lo_[0]);
    const unsigned dy = static_cast<unsigned>(k[1] - lo_[1]);
    const unsigned dz = static_cast<unsigned>(k[2] - lo_[2]);
    if (dx >= side_ || dy >= side_ || dz >= side_) {
      return std::nullopt;
    }
    return dx + std::size_t{side_} * (dy + std::size_t{side_} * dz);
  }
  /// Inlined into the ray's walk, whose every step calls it: called, it was a fifth of the
  /// mapper's time, its window's path a few instructions.
  [[gnu::always_inline]] void insert(const octomap::OcTreeKey& key, bool occupied)
  {
    if (const auto at = windowIndex(key)) {
      std::uint64_t& word = seen_[*at >> 6];
      const std::uint64_t bit = std::uint64_t{1} << (*at & 63);
      if ((word & bit) == 0) {
        word |= bit;
        order_.push_back(pack(key));
      }
      if (occupied) {
        occupied_[*at >> 6] |= bit;
      }
      return;
    }
    insertHashed(pack(key), occupied ? kOccupiedBit : 0);
  }
  void insertHashed(std::uint64_t key, std::uint64_t flag);
  std::size_t find(std::uint64_t key) const;  ///< the slot holding a hashed key
  void grow();

  // The window: keys lo_ ... lo_ + side_ − 1 per axis (side_ 0: none), a bit each.
  std::array<int, 3> lo_{};
  unsigned side_ = 0;
  std::vector<std::uint64_t> seen_;
  std::vector<std::uint64_t> occupied_;
  // The keys outside it.
  std::vector<std::uint64_t> slots_;   // key | flag, or kEmpty
  std::vector<std::uint32_t> used_;    // the slots in use
  int shift_ = 64;                     // 64 − log2(capacity)
  std::vector<std::uint64_t> order_;   // every key, packed, in insertion order
};

class MapTree : public octomap::OcTree {
public:
  explicit MapTree(double voxel_size) : octomap::OcTree(voxel_size) {}

  /// OcTree::insertPointCloud(cloud, origin, max_range) (lazy_eval off, not discretized),
  /// with the voxels whose classification changed appended to `changes`, each once.
  void insertPointCloudTracked(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range,
                               std::vector<KeyChange>& changes);

  /// The same changes, the tree's own update left to settle(): in a box of at most
  /// kMaxLeafVoxels voxels, each voxel's log-odds are kept beside the tree (its leaves'
  /// values, voxel by voxel), so a scan's changes follow from them and the scan's keys, a
  /// look-up a key, without descending the tree. Until settle() the tree is the one before
  /// the scans so reported; read it only after. Without such a box the tree is updated at once.
  /// The tree's probabilities and clamping bounds must not change while updates are pending.
  void reportPointCloud(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range,
                        std::vector<KeyChange>& changes);
  /// Brings the tree up to date with every scan reported since it last was: each voxel those
  /// scans changed is set once to its value now, in one descent, however many of them
  /// updated it. The tree OctoMap's insertPointCloud would have built from those scans, whose
  /// pruning leaves a tree that depends only on its voxels' values. Settling once for many
  /// scans costs a descent per voxel instead of one per update.
  void settle();
  /// Whether each voxel's log-odds are kept beside the tree (reportPointCloud leaves the tree
  /// to settle()); else every scan updates the tree at once.
  bool keepsLeaves() const { return leaves_ != nullptr; }
  /// The voxels' log-odds kept beside the tree, as the settled tree's leaves, when the tree
  /// holds nothing outside the box (one read from a stream may): its image then comes from
  /// them (boxImage), settled or not. The words are this tree's, changed by the next scan.
  std::optional<VoxelBox> voxelBox() const;
  /// The words of voxelBox().
  std::size_t voxelCount() const { return leaf_count_; }
  /// No voxel is known, settled or not: the tree is empty and stays so when settled.
  bool holdsNoVoxel() const { return root == nullptr && touched_.empty(); }
  /// A flag a block of the box (blockOf): set when a voxel of it changed since the last call
  /// (all set after a resync), into `changed`; the flags start again clear.
  void takeChangedBlocks(std::vector<std::uint8_t>& changed);

  /// Only voxels whose keys lie in [lo, hi] (inclusive, per axis) are updated from now on, as
  /// OctoMap's bounding-box limit does: rays still run their whole length, what they cross
  /// outside the box is left alone. A box of at most kMaxBoundVoxels voxels also keeps, for
  /// each of its voxels, whether it sits at a clamping bound (below), and one of at most
  /// kMaxLeafVoxels its voxels' log-odds (reportPointCloud).
  void limitTo(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi);

  /// The tree was changed other than by this class's insertions (read from a stream,
  /// cleared): updates still pending (of the tree before) are dropped, what was known of its
  /// voxels' clamping bounds too, and their log-odds are read again from the tree.
  void resync();

  /// Updates that OctoMap's early abort would have dropped (the voxel already at the
  /// clamping bound the update pushes towards) and that were dropped without a descent,
  /// from the voxel's bits: a measure of what the bits save.
  std::uint64_t updatesSkippedAtBounds() const { return skipped_at_bounds_; }

  /// The largest box whose voxels' clamping bounds are kept: two bits a voxel, 32 MiB.
  static constexpr std::size_t kMaxBoundVoxels = std::size_t{1} << 27;
  /// The largest box whose voxels' log-odds are kept beside the tree: four bytes a voxel,
  /// 128 MiB of address space, of which only the pages of voxels ever known are touched.
  static constexpr std::size_t kMaxLeafVoxels = std::size_t{1} << 25;

private:
  /// The scan's keys into keys_ (the free along the rays, the occupied at the hits).
  void collectKeys(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range);
  /// One update of the scan reported from the voxel's log-odds kept beside the tree.
  void reportUpdate(const octomap::OcTreeKey& key, bool occupied, std::vector<KeyChange>& changes);

  bool inBox(const octomap::OcTreeKey& k) const
  {
    return !limited_ || (k[0] >= box_lo_[0] && k[0] <= box_hi_[0] && k[1] >= box_lo_[1] && k[1] <= box_hi_[1] &&
                         k[2] >= box_lo_[2] && k[2] <= box_hi_[2]);
  }
  /// Puts the keys of the ray from `origin` to `end` (OctoMap's computeRayKeys: the voxels
  /// crossed, without the end's) that lie in the box into the scan's key set as free.
  void freeAlongRay(const octomap::point3d& origin, const octomap::point3d& end);
  /// The key has passed the box along `axis`, moving that way (`step`'s sign) or not at all.
  bool beyondBox(const octomap::OcTreeKey& key, unsigned axis, int step) const;
  /// OcTree::updateNode(key, occupied) in one descent; the voxel's classification after it
  /// (true: occupied) when that changed, nothing when it did not. The descent starts where
  /// the previous update's path and this key's part (a ray's voxels come one after another).
  std::optional<bool> updateTracked(const octomap::OcTreeKey& key, bool occupied);
  /// The descent and the way back up of updateTracked, and of settle() setting a voxel's
  /// value: `unchanged(value)` of a voxel in the tree (its leaf's value, or the pruned node's
  /// holding it) says the update leaves it as it is; else `update(leaf)` sets the voxel's leaf,
  /// created (unknown) or expanded out of a pruned node as OcTree::updateNodeRecurs does.
  template <class Unchanged, class Update>
  std::optional<bool> descendAndUpdate(const octomap::OcTreeKey& key, Unchanged unchanged, Update update);

  /// A voxel and the log-odds the tree is to hold for it.
  struct VoxelValue {
    octomap::OcTreeKey key;
    float log_odds;
  };
  /// The voxels the scans reported since the tree was last settled changed, each with its
  /// value now: the tree forgets them, for settle(voxels) to set.
  std::vector<VoxelValue> detachUnsettled();
  /// Sets each voxel of `voxels` (detachUnsettled's) to its value.
  void settle(const std::vector<VoxelValue>& voxels);

  ScanKeySet keys_;
  // The last update's path from the root: path_[0 ... path_valid_] still exist as they were
  // (-1: none, as at the start of a scan; the tree may have changed since the last one).
  std::array<octomap::OcTreeNode*, 17> path_{};
  octomap::OcTreeKey path_key_;
  int path_valid_ = -1;
  bool limited_ = false;  // updates only inside [box_lo_, box_hi_]
  octomap::OcTreeKey box_lo_;
  octomap::OcTreeKey box_hi_;

  // Within the box: two bits a voxel, set while its value (its leaf's, or the pruned node's
  // holding it) is known to equal the lower clamping bound (bit 0) or the upper (bit 1).
  // Each voxel's value changes only by an update of its own key (pruning and expanding keep
  // values), so a bit set when an update leaves the voxel at a bound holds until the next
  // update of that voxel, which sets or clears it again. An update towards the bound a
  // voxel's bit says it sits at changes nothing (OctoMap's early abort): it is dropped
  // without descending the tree, the descent's cache misses being most of an update's cost.
  // A bit never set only costs the descent. Empty: no box, or one too large.
  std::size_t boundIndex(const octomap::OcTreeKey& k) const
  {
    return (k[0] - box_lo_[0]) +
           box_side_[0] * ((k[1] - box_lo_[1]) + box_side_[1] * std::size_t{static_cast<unsigned>(k[2] - box_lo_[2])});
  }
  bool atBound(std::size_t voxel, bool occupied) const
  {
    const std::size_t bit = 2 * voxel + (occupied ? 1 : 0);
    return ((bounds_[bit >> 6] >> (bit & 63)) & 1U) != 0;
  }
  /// Records a voxel's value after its update: at the lower bound, the upper, or neither.
  void noteBounds(const octomap::OcTreeKey& key, float value);
  std::vector<std::uint64_t> bounds_;

  // Within the box: each voxel's log-odds as the tree holds them once settled, as a word
  // (its float's bits XOR kUnknownLeaf: 0, as the zeroed pages give, for a voxel not in the
  // tree). Empty: no box, or one too large.
  struct FreeDeleter {
    void operator()(void* p) const { std::free(p); }
  };
  static constexpr std::uint32_t kUnknownLeaf = 0x7FBADBADU;  // a NaN no update makes
  std::unique_ptr<std::uint32_t[], FreeDeleter> leaves_;
  std::size_t leaf_count_ = 0;
  bool tree_in_box_ = true;  // the tree holds no voxel outside the box (resync)
  std::vector<std::uint8_t> changed_blocks_;  // takeChangedBlocks'
  // The voxels whose value changed since the tree was last settled, each once (its bit set
  // in unsettled_ while it is listed). Empty with no leaves kept.
  std::vector<octomap::OcTreeKey> touched_;
  std::unique_ptr<std::uint64_t[], FreeDeleter> unsettled_;
  octomap::OcTreeNode scratch_leaf_;  // a voxel's leaf as reportUpdate works it out

  std::array<std::size_t, 2> box_side_{};  // voxels along x and y
  float bounds_min_ = 0.0F;                 // the clamping bounds the bits were set under
  float bounds_max_ = 0.0F;
  std::uint64_t skipped_at_bounds_ = 0;
};

}  // namespace quad::mapping
