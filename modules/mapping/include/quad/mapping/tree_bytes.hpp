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

/// The whole .bt file of `tree`: its header, then each inner node's children as free,
/// occupied, unknown or inner (two bits each), depth first.
std::vector<std::uint8_t> binaryTreeBytes(const octomap::OcTree& tree);

/// The node data of `tree`: each node's log-odds and a mask of the children it has, depth
/// first (empty for an empty tree).
std::vector<std::uint8_t> treeDataBytes(const octomap::OcTree& tree);

}  // namespace quad::mapping
