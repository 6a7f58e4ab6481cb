// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// OctoMap's two byte formats of a tree, written straight into a buffer: the bytes of
/// `OcTree::writeBinaryConst` (a .bt file: the snapshot the mapper publishes and exports) and
/// of `OcTree::writeData` (the node data of an .ot file: the mapper's checkpoint). OctoMap
/// writes them through one stream call per byte or value, which cost the running mapper
/// more than its ray casting; the bytes are the same.

#include <cstdint>
#include <vector>

#include <octomap/OcTree.h>

namespace quad::mapping {

/// The whole .bt file of `tree`: its header, then each inner node's children as free,
/// occupied, unknown or inner (two bits each), depth first.
std::vector<std::uint8_t> binaryTreeBytes(const octomap::OcTree& tree);

/// The node data of `tree`: each node's log-odds and a mask of the children it has, depth
/// first (empty for an empty tree).
std::vector<std::uint8_t> treeDataBytes(const octomap::OcTree& tree);

}  // namespace quad::mapping
