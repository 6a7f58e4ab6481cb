// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/tree_bytes.hpp"

#include <cstring>
#include <sstream>
#include <string>

namespace quad::mapping {

namespace {

using Node = octomap::OcTreeNode;

/// One depth-first walk over the inner nodes; a leaf is written from its parent, so it costs
/// no call of its own.
class TreeWalk {
public:
  TreeWalk(const octomap::OcTree& tree, std::vector<std::uint8_t>* binary, std::uint8_t* data)
      : tree_(tree), binary_(binary), data_(data)
  {
  }

  /// Writes the root and all below it: both formats write the root as an inner node, with
  /// or without children (a root pruned whole is a leaf, though).
  void root(const Node* node)
  {
    leaves_ += tree_.nodeHasChildren(node) ? 0U : 1U;
    inner(node);
  }

  std::size_t leaves() const { return leaves_; }

private:
  /// The data of an inner node, then the binary record of its children (two bits each,
  /// children 0-3 in the first byte and 4-7 in the second, child 0 and 4 in the lowest
  /// bits: 1 free, 2 occupied, 3 inner, 0 unknown), then each child in order: a leaf's data
  /// at once, an inner child's walk.
  void inner(const Node* node)
  {
    const Node* children[8] = {};
    bool has_children[8] = {};
    std::uint8_t mask = 0;
    std::uint8_t halves[2] = {0, 0};
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree_.nodeChildExists(node, i)) {
        continue;
      }
      const Node* child = tree_.getNodeChild(node, i);
      children[i] = child;
      has_children[i] = tree_.nodeHasChildren(child);
      mask |= static_cast<std::uint8_t>(1U << i);
      const unsigned code = has_children[i] ? 3U : tree_.isNodeOccupied(child) ? 2U : 1U;
      halves[i / 4] |= static_cast<std::uint8_t>(code << (2 * (i % 4)));
    }
    putData(node, mask);
    if (binary_ != nullptr) {
      binary_->push_back(halves[0]);
      binary_->push_back(halves[1]);
    }
    for (unsigned i = 0; i < 8; ++i) {
      if (has_children[i]) {
        inner(children[i]);
      } else if (children[i] != nullptr) {
        putData(children[i], 0);
        ++leaves_;
      }
    }
  }

  void putData(const Node* node, std::uint8_t mask)
  {
    if (data_ == nullptr) {
      return;
    }
    const float value = node->getValue();
    std::memcpy(data_, &value, sizeof(value));
    data_[sizeof(value)] = mask;
    data_ += sizeof(value) + 1;
  }

  const octomap::OcTree& tree_;
  std::vector<std::uint8_t>* binary_;
  std::uint8_t* data_;
  std::size_t leaves_ = 0;
};

std::vector<std::uint8_t> binaryHeader(const octomap::OcTree& tree)
{
  // As AbstractOccupancyOcTree::writeBinaryConst writes it (the resolution in the stream's
  // default format).
  std::ostringstream header;
  header << "# Octomap OcTree binary file\n"
         << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
         << "id " << tree.getTreeType() << "\n"
         << "size " << tree.size() << "\n"
         << "res " << tree.getResolution() << "\n"
         << "data\n";
  const std::string text = header.str();
  return {text.begin(), text.end()};
}

}  // namespace

TreeImage treeImage(const octomap::OcTree& tree, bool with_data)
{
  TreeImage image;
  image.binary = binaryHeader(tree);
  image.binary.reserve(image.binary.size() + 2 * tree.size());
  if (with_data) {
    image.data.resize((sizeof(float) + 1) * tree.size());
  }
  std::size_t leaves = 0;
  if (tree.getRoot() != nullptr) {
    TreeWalk walk(tree, &image.binary, with_data ? image.data.data() : nullptr);
    walk.root(tree.getRoot());
    leaves = walk.leaves();
  }
  // OcTreeBaseImpl::memoryUsage(), with the leaves counted by the walk above.
  using Base = octomap::OcTreeBaseImpl<octomap::OcTreeNode, octomap::AbstractOccupancyOcTree>;
  image.memory_bytes = sizeof(Base) + tree.memoryUsageNode() * tree.size() +
                       (tree.size() - leaves) * sizeof(octomap::OcTreeNode* [8]);
  image.nodes = tree.size();
  return image;
}

std::vector<std::uint8_t> binaryTreeBytes(const octomap::OcTree& tree) { return treeImage(tree, false).binary; }

std::vector<std::uint8_t> treeDataBytes(const octomap::OcTree& tree)
{
  std::vector<std::uint8_t> data((sizeof(float) + 1) * tree.size());
  if (tree.getRoot() != nullptr) {
    TreeWalk(tree, nullptr, data.data()).root(tree.getRoot());
  }
  return data;
}

}  // namespace quad::mapping
