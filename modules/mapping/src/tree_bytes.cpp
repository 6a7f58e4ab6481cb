// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/tree_bytes.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <limits>
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

/// The header AbstractOccupancyOcTree::writeBinaryConst writes for a tree of type `id`,
/// `nodes` nodes and `resolution` (in the stream's default format).
std::vector<std::uint8_t> binaryHeader(const std::string& id, std::size_t nodes, double resolution)
{
  std::ostringstream header;
  header << "# Octomap OcTree binary file\n"
         << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
         << "id " << id << "\n"
         << "size " << nodes << "\n"
         << "res " << resolution << "\n"
         << "data\n";
  const std::string text = header.str();
  return {text.begin(), text.end()};
}

/// OcTreeBaseImpl::memoryUsage() of a tree of `nodes` nodes, `leaves` of them leaves.
std::size_t memoryBytes(std::size_t nodes, std::size_t leaves)
{
  using Base = octomap::OcTreeBaseImpl<octomap::OcTreeNode, octomap::AbstractOccupancyOcTree>;
  return sizeof(Base) + sizeof(octomap::OcTreeNode) * nodes + (nodes - leaves) * sizeof(octomap::OcTreeNode* [8]);
}

/// The walk of TreeWalk over the tree a box of voxels makes, without the tree: depth first
/// over the cubes of each depth that overlap the box. A node's record and data are written
/// before its children's, so their place is kept and filled once the children are known;
/// a node found to be a leaf of one value (OctoMap would have pruned it) or all unknown takes
/// back what its children wrote.
class BoxWalk {
public:
  BoxWalk(const VoxelBox& box, std::vector<std::uint8_t>& records, std::vector<std::uint8_t>* data,
          BoxImageCache* cache, const std::vector<std::uint8_t>* changed)
      : box_(box), records_(records), data_(data), cache_(cache), changed_(changed)
  {
    for (unsigned a = 0; a < 3; ++a) {
      side_[a] = box.hi[a] >= box.lo[a] ? std::size_t{box.hi[a]} - box.lo[a] + 1U : 0U;
    }
  }

  /// What a node (or a voxel) is once its cube is walked.
  struct Cube {
    bool known = false;  ///< a voxel in it is known: the node exists
    bool leaf = false;   ///< every voxel in it is known, with one value: a leaf
    float value = 0.0F;  ///< a leaf's value, an inner node's greatest child's
  };

  /// Walks the root: both formats write it as an inner node, even a root pruned whole.
  void root()
  {
    const Cube cube = inner(0, {0, 0, 0});
    if (cube.known && cube.leaf) {
      putData(cube.value, 0);
      records_.push_back(0);
      records_.push_back(0);
      ++leaves_;
    }
  }

  std::size_t nodes() const { return inner_ + leaves_; }
  std::size_t leaves() const { return leaves_; }

private:
  static constexpr unsigned kTreeDepth = 16;  // an OcTree's
  static constexpr std::size_t kDataBytes = sizeof(float) + 1;

  /// The node at `depth` whose cube starts at key `at`, above the voxels' parents: a block's
  /// from the cache when it holds the block unchanged.
  Cube inner(unsigned depth, std::array<unsigned, 3> at)
  {
    if (cache_ == nullptr || depth != kTreeDepth - kBlockShift) {
      return walk(depth, at);
    }
    const octomap::OcTreeKey key(static_cast<octomap::key_type>(std::max<unsigned>(at[0], box_.lo[0])),
                                 static_cast<octomap::key_type>(std::max<unsigned>(at[1], box_.lo[1])),
                                 static_cast<octomap::key_type>(std::max<unsigned>(at[2], box_.lo[2])));
    const std::size_t index = blockOf(box_.lo, box_.hi, key);
    BoxImageCache::Block& block = cache_->blocks[index];
    if (!block.walked || (changed_ != nullptr && (*changed_)[index] != 0)) {
      const std::size_t data_at = data_ != nullptr ? data_->size() : 0;
      const std::size_t record_at = records_.size();
      const std::size_t inner_before = inner_;
      const std::size_t leaves_before = leaves_;
      const Cube cube = walk(depth, at);
      block.walked = true;
      block.known = cube.known;
      block.leaf = cube.leaf;
      block.value = cube.value;
      block.records.assign(records_.begin() + static_cast<std::ptrdiff_t>(record_at), records_.end());
      if (data_ != nullptr) {
        block.data.assign(data_->begin() + static_cast<std::ptrdiff_t>(data_at), data_->end());
      }
      block.inner = inner_ - inner_before;
      block.leaves = leaves_ - leaves_before;
      return cube;
    }
    records_.insert(records_.end(), block.records.begin(), block.records.end());
    if (data_ != nullptr) {
      data_->insert(data_->end(), block.data.begin(), block.data.end());
    }
    inner_ += block.inner;
    leaves_ += block.leaves;
    return {block.known, block.leaf, block.value};
  }

  /// The node at `depth` whose cube starts at key `at`, walked.
  Cube walk(unsigned depth, std::array<unsigned, 3> at)
  {
    const unsigned half = 1U << (kTreeDepth - 1U - depth);  // a child's side, in voxels
    const std::size_t data_at = data_ != nullptr ? data_->size() : 0;
    const std::size_t record_at = records_.size();
    const std::size_t inner_before = inner_;
    const std::size_t leaves_before = leaves_;
    if (data_ != nullptr) {
      data_->resize(data_at + kDataBytes);
    }
    records_.resize(record_at + 2);
    std::array<Cube, 8> children{};
    for (unsigned i = 0; i < 8; ++i) {
      const std::array<unsigned, 3> child = childAt(at, i, half);
      if (!overlaps(child, half)) {
        continue;
      }
      children[i] = half == 2 ? parentOfVoxels(child) : inner(depth + 1, child);
      if (children[i].known && children[i].leaf) {
        putData(children[i].value, 0);
        ++leaves_;
      }
    }
    const Cube cube = describe(children);
    if (!cube.known || cube.leaf) {
      // No node, or a leaf (its parent writes it): what its children wrote goes.
      if (data_ != nullptr) {
        data_->resize(data_at);
      }
      records_.resize(record_at);
      inner_ = inner_before;
      leaves_ = leaves_before;
      return cube;
    }
    ++inner_;
    putNode(record_at, data_at, children, cube.value);
    return cube;
  }

  /// A node whose children are voxels: found before anything is written, so a leaf or a
  /// node of none costs no writing.
  Cube parentOfVoxels(std::array<unsigned, 3> at)
  {
    std::array<Cube, 8> children{};
    for (unsigned i = 0; i < 8; ++i) {
      const std::array<unsigned, 3> key = childAt(at, i, 1);
      if (overlaps(key, 1)) {
        children[i] = voxel(key);
      }
    }
    const Cube cube = describe(children);
    if (!cube.known || cube.leaf) {
      return cube;
    }
    ++inner_;
    const std::size_t data_at = data_ != nullptr ? data_->size() : 0;
    const std::size_t record_at = records_.size();
    if (data_ != nullptr) {
      data_->resize(data_at + kDataBytes);
    }
    records_.resize(record_at + 2);
    putNode(record_at, data_at, children, cube.value);
    for (const Cube& c : children) {
      if (c.known) {
        putData(c.value, 0);
        ++leaves_;
      }
    }
    return cube;
  }

  /// OctoMap's child index: bit 0 along x, bit 1 along y, bit 2 along z.
  static std::array<unsigned, 3> childAt(const std::array<unsigned, 3>& at, unsigned i, unsigned half)
  {
    return {at[0] + ((i & 1U) != 0 ? half : 0U), at[1] + ((i & 2U) != 0 ? half : 0U),
            at[2] + ((i & 4U) != 0 ? half : 0U)};
  }

  /// The node of these children: none when none is known; a leaf of their value when all
  /// eight are leaves of one value (OcTreeBaseImpl::isNodeCollapsible, pruneNode copying
  /// child 0's); else inner, with the greatest of theirs (OcTreeNode::getMaxChildLogOdds).
  static Cube describe(const std::array<Cube, 8>& children)
  {
    bool any = false;
    bool one_value = true;
    float greatest = -std::numeric_limits<float>::max();
    for (const Cube& c : children) {
      one_value = one_value && c.known && c.leaf && c.value == children[0].value;
      if (c.known) {
        any = true;
        greatest = c.value > greatest ? c.value : greatest;
      }
    }
    if (!any) {
      return {};
    }
    return one_value ? Cube{true, true, children[0].value} : Cube{true, false, greatest};
  }

  /// An inner node's data and record at the places kept for them.
  void putNode(std::size_t record_at, std::size_t data_at, const std::array<Cube, 8>& children, float value)
  {
    std::uint8_t mask = 0;
    std::uint8_t halves[2] = {0, 0};
    for (unsigned i = 0; i < 8; ++i) {
      const Cube& c = children[i];
      if (!c.known) {
        continue;
      }
      mask |= static_cast<std::uint8_t>(1U << i);
      const unsigned code = !c.leaf ? 3U : c.value >= box_.occupied_log_odds ? 2U : 1U;
      halves[i / 4] |= static_cast<std::uint8_t>(code << (2 * (i % 4)));
    }
    if (data_ != nullptr) {
      std::memcpy(data_->data() + data_at, &value, sizeof(value));
      (*data_)[data_at + sizeof(value)] = mask;
    }
    records_[record_at] = halves[0];
    records_[record_at + 1] = halves[1];
  }

  Cube voxel(const std::array<unsigned, 3>& key) const
  {
    const std::size_t index =
        (key[0] - box_.lo[0]) + side_[0] * ((key[1] - box_.lo[1]) + side_[1] * std::size_t{key[2] - box_.lo[2]});
    const std::uint32_t word = box_.words[index];
    if (word == 0) {
      return {};
    }
    return {true, true, std::bit_cast<float>(word ^ box_.mark)};
  }

  bool overlaps(const std::array<unsigned, 3>& at, unsigned side) const
  {
    for (unsigned a = 0; a < 3; ++a) {
      if (at[a] + side - 1U < box_.lo[a] || at[a] > box_.hi[a]) {
        return false;
      }
    }
    return true;
  }

  void putData(float value, std::uint8_t mask)
  {
    if (data_ == nullptr) {
      return;
    }
    std::uint8_t bytes[kDataBytes];
    std::memcpy(bytes, &value, sizeof(value));
    bytes[sizeof(value)] = mask;
    data_->insert(data_->end(), bytes, bytes + kDataBytes);
  }

  const VoxelBox& box_;
  std::array<std::size_t, 3> side_{};
  std::vector<std::uint8_t>& records_;
  std::vector<std::uint8_t>* data_;
  BoxImageCache* cache_;
  const std::vector<std::uint8_t>* changed_;
  std::size_t inner_ = 0;
  std::size_t leaves_ = 0;
};

}  // namespace

TreeImage treeImage(const octomap::OcTree& tree, bool with_data)
{
  TreeImage image;
  image.binary = binaryHeader(tree.getTreeType(), tree.size(), tree.getResolution());
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
  image.memory_bytes = memoryBytes(tree.size(), leaves);  // the leaves counted by the walk above
  image.nodes = tree.size();
  return image;
}

std::size_t blockCount(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi)
{
  for (unsigned a = 0; a < 3; ++a) {
    if (hi[a] < lo[a]) {
      return 0;
    }
  }
  return blockOf(lo, hi, hi) + 1;
}

TreeImage boxImage(const VoxelBox& box, bool with_data, BoxImageCache* cache, const std::vector<std::uint8_t>* changed)
{
  const std::size_t blocks = blockCount(box.lo, box.hi);
  if (changed != nullptr && changed->size() != blocks) {
    changed = nullptr;
    cache = nullptr;  // not this box's blocks: nothing is known to be unchanged
  }
  if (cache != nullptr && (cache->lo != box.lo || cache->hi != box.hi || cache->with_data != with_data ||
                           cache->blocks.size() != blocks)) {
    *cache = BoxImageCache{box.lo, box.hi, with_data, std::vector<BoxImageCache::Block>(blocks)};
  }
  std::vector<std::uint8_t> records;
  TreeImage image;
  BoxWalk walk(box, records, with_data ? &image.data : nullptr, cache, changed);
  walk.root();
  image.nodes = walk.nodes();
  image.memory_bytes = memoryBytes(walk.nodes(), walk.leaves());
  image.binary = binaryHeader("OcTree", walk.nodes(), box.resolution);  // the mapper's tree is an OcTree
  image.binary.insert(image.binary.end(), records.begin(), records.end());
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
