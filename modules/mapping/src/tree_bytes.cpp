// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/tree_bytes.hpp"

#include <array>
#include <cstring>
#include <sstream>
#include <string>

namespace quad::mapping {

namespace {

using Node = octomap::OcTreeNode;

/// Two bits per child, children 0-3 in the first byte and 4-7 in the second, child 0 and 4
/// in the lowest bits: 1 free, 2 occupied, 3 inner, 0 unknown; then the inner children's own.
void appendBinaryNode(const octomap::OcTree& tree, const Node* node, std::vector<std::uint8_t>& out)
{
  std::array<const Node*, 8> inner{};  // the children that have children of their own
  std::uint8_t halves[2] = {0, 0};
  for (unsigned i = 0; i < 8; ++i) {
    if (!tree.nodeChildExists(node, i)) {
      continue;
    }
    const Node* child = tree.getNodeChild(node, i);
    unsigned code = 1U;
    if (tree.nodeHasChildren(child)) {
      inner[i] = child;
      code = 3U;
    } else if (tree.isNodeOccupied(child)) {
      code = 2U;
    }
    halves[i / 4] |= static_cast<std::uint8_t>(code << (2 * (i % 4)));
  }
  out.push_back(halves[0]);
  out.push_back(halves[1]);
  for (const Node* child : inner) {
    if (child != nullptr) {
      appendBinaryNode(tree, child, out);
    }
  }
}

void appendDataNode(const octomap::OcTree& tree, const Node* node, std::vector<std::uint8_t>& out)
{
  std::array<const Node*, 8> children{};
  std::uint8_t mask = 0;
  for (unsigned i = 0; i < 8; ++i) {
    if (tree.nodeChildExists(node, i)) {
      children[i] = tree.getNodeChild(node, i);
      mask |= static_cast<std::uint8_t>(1U << i);
    }
  }
  const float value = node->getValue();
  const std::size_t at = out.size();
  out.resize(at + sizeof(value) + 1);
  std::memcpy(out.data() + at, &value, sizeof(value));
  out[at + sizeof(value)] = mask;
  for (const Node* child : children) {
    if (child != nullptr) {
      appendDataNode(tree, child, out);
    }
  }
}

}  // namespace

std::vector<std::uint8_t> binaryTreeBytes(const octomap::OcTree& tree)
{
  // The header as AbstractOccupancyOcTree::writeBinaryConst writes it (the resolution in the
  // stream's default format).
  std::ostringstream header;
  header << "# Octomap OcTree binary file\n"
         << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
         << "id " << tree.getTreeType() << "\n"
         << "size " << tree.size() << "\n"
         << "res " << tree.getResolution() << "\n"
         << "data\n";
  const std::string text = header.str();
  std::vector<std::uint8_t> out(text.begin(), text.end());
  out.reserve(text.size() + 2 * tree.size());
  if (tree.getRoot() != nullptr) {
    appendBinaryNode(tree, tree.getRoot(), out);
  }
  return out;
}

std::vector<std::uint8_t> treeDataBytes(const octomap::OcTree& tree)
{
  std::vector<std::uint8_t> out;
  out.reserve((sizeof(float) + 1) * tree.size());
  if (tree.getRoot() != nullptr) {
    appendDataNode(tree, tree.getRoot(), out);
  }
  return out;
}

}  // namespace quad::mapping
