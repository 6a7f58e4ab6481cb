// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// OctoMap's two byte formats of a tree, written straight into a buffer: the bytes of
/// `OcTree::writeBinaryConst` (a .bt file: the snapshot the mapper publishes and exports) and
/// of `OcTree::writeData` (the node data of an .ot file: the mapper's checkpoint). OctoMap
/// writes them through one stream call per byte or value, which cost the running mapper
/// more than its ray casting; the bytes are the same.
///
/// Walking a large tree costs mostly the cache misses of reaching its nodes, so both formats
/// and the tree's memory use come from one walk when the mapper wants them together (a
/// snapshot with its checkpoint).
///
/// A bounded map's voxels are also kept as a flat box of log-odds (MapTree::voxelBox), and
/// its tree is a function of them: OctoMap prunes a node wherever its eight children are
/// leaves of one value, and an inner node holds its children's greatest. The same bytes then
/// come from the box without the tree (boxImage): no tree to bring up to date first.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <octomap/OcTree.h>

namespace quad::mapping {

/// What one walk of a tree gives.
struct TreeImage {
  std::vector<std::uint8_t> binary;  ///< the .bt file (binaryTreeBytes)
  std::vector<std::uint8_t> data;    ///< the node data (treeDataBytes); empty unless asked for
  std::size_t memory_bytes = 0;      ///< what `OcTree::memoryUsage()` says, without its own walk
  std::size_t nodes = 0;             ///< the tree's nodes (`OcTree::size()`)
};

/// Both formats (the node data only `with_data`) and the memory use of `tree`, in one walk.
TreeImage treeImage(const octomap::OcTree& tree, bool with_data);

/// A box of voxels at a tree's finest depth, each unknown or with its log-odds: the leaves of
/// an OcTree that holds nothing outside the box.
struct VoxelBox {
  octomap::OcTreeKey lo;                ///< the box's first key along each axis
  octomap::OcTreeKey hi;                ///< and its last (inclusive)
  const std::uint32_t* words = nullptr;  ///< a word a voxel, x fastest, then y, then z
  std::uint32_t mark = 0;               ///< a word is 0 for an unknown voxel, else its log-odds' bits XOR mark
  double resolution = 0.0;              ///< [m] the tree's
  float occupied_log_odds = 0.0F;       ///< a voxel at or above is occupied (the tree's threshold)
};

/// A box's voxels in blocks: cubes of 16 voxels a side on the octree's own grid (each an
/// octree node 12 levels below the root), cut to the box; numbered x fastest, then y, then z.
inline constexpr unsigned kBlockShift = 4;
/// The blocks of the box [lo, hi].
std::size_t blockCount(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi);
/// The block of `key`, a key in the box [lo, hi].
inline std::size_t blockOf(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi, const octomap::OcTreeKey& key)
{
  const auto block = [](octomap::key_type k) { return std::size_t{k} >> kBlockShift; };
  const auto along = [&](unsigned a) { return block(key[a]) - block(lo[a]); };
  const auto side = [&](unsigned a) { return block(hi[a]) - block(lo[a]) + 1U; };
  return along(0) + side(0) * (along(1) + side(1) * along(2));
}

/// What boxImage keeps of a box's image for the next one (read and written by boxImage
/// alone): each block's part of it, taken again for a block whose voxels did not change.
struct BoxImageCache {
  struct Block {
    bool walked = false;  ///< the fields below hold its last walk
    bool known = false;   ///< the block's node exists
    bool leaf = false;    ///< it is a leaf of `value` (its parent writes it)
    float value = 0.0F;
    std::vector<std::uint8_t> records;  ///< its binary records, and its subtree's
    std::vector<std::uint8_t> data;     ///< its node data, and its subtree's
    std::size_t inner = 0;              ///< inner nodes in its subtree, itself included
    std::size_t leaves = 0;             ///< leaves in its subtree, below it
  };
  octomap::OcTreeKey lo;
  octomap::OcTreeKey hi;
  bool with_data = false;
  std::vector<Block> blocks;
};

/// What treeImage gives for the OcTree whose leaves `box` holds, from the box alone. With a
/// cache and the blocks changed since the image it holds (`changed`, a flag a block), the
/// unchanged blocks' parts come from it, and it keeps this image's.
TreeImage boxImage(const VoxelBox& box, bool with_data, BoxImageCache* cache = nullptr,
                   const std::vector<std::uint8_t>* changed = nullptr);

/// The whole .bt file of `tree`: its header, then each inner node's children as free,
/// occupied, unknown or inner (two bits each), depth first.
std::vector<std::uint8_t> binaryTreeBytes(const octomap::OcTree& tree);

/// The node data of `tree`: each node's log-odds and a mask of the children it has, depth
/// first (empty for an empty tree).
std::vector<std::uint8_t> treeDataBytes(const octomap::OcTree& tree);

}  // namespace quad::mapping
