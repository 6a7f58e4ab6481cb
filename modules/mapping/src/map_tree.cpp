// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/map_tree.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <optional>

namespace quad::mapping {

void ScanKeySet::clear(const octomap::OcTreeKey& centre, unsigned radius)
{
  for (const std::uint64_t v : order_) {
    if (const auto at = windowIndex(unpack(v))) {
      seen_[*at >> 6] = 0;  // clears the word: every bit set in it was a key of this scan
      occupied_[*at >> 6] = 0;
    }
  }
  for (const std::uint32_t slot : used_) {
    slots_[slot] = kEmpty;
  }
  used_.clear();
  order_.clear();
  side_ = radius > 0 && radius <= kMaxWindowRadius ? 2 * radius + 1 : 0;
  for (std::size_t a = 0; a < 3; ++a) {
    lo_[a] = static_cast<int>(centre[static_cast<unsigned>(a)]) - static_cast<int>(radius);
  }
  const std::size_t words = (std::size_t{side_} * side_ * side_ + 63) / 64;
  if (seen_.size() < words) {
    seen_.assign(words, 0);
    occupied_.assign(words, 0);
  }
}

void ScanKeySet::insertHashed(std::uint64_t key, std::uint64_t flag)
{
  if (slots_.empty()) {
    shift_ = 64 - 16;
    slots_.assign(std::size_t{1} << 16, kEmpty);
  }
  const std::size_t mask = slots_.size() - 1;
  // Fibonacci hashing: the top bits of key · 2^64/φ spread neighbouring keys apart.
  for (std::size_t i = (key * 0x9E3779B97F4A7C15ULL) >> shift_;; i = (i + 1) & mask) {
    std::uint64_t& slot = slots_[i];
    if (slot == kEmpty) {
      slot = key | flag;
      used_.push_back(static_cast<std::uint32_t>(i));
      order_.push_back(key);
      if (used_.size() * 2 > slots_.size()) {
        grow();
      }
      return;
    }
    if ((slot & kKeyMask) == key) {
      slot |= flag;
      return;
    }
  }
}

std::size_t ScanKeySet::find(std::uint64_t key) const
{
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = (key * 0x9E3779B97F4A7C15ULL) >> shift_;; i = (i + 1) & mask) {
    if ((slots_[i] & kKeyMask) == key) {
      return i;
    }
  }
}

void ScanKeySet::grow()
{
  std::vector<std::uint64_t> held;
  held.reserve(used_.size());
  for (const std::uint32_t slot : used_) {
    held.push_back(slots_[slot]);
  }
  slots_.assign(slots_.size() * 2, kEmpty);
  --shift_;
  used_.clear();
  const std::size_t mask = slots_.size() - 1;
  for (const std::uint64_t v : held) {
    std::size_t i = ((v & kKeyMask) * 0x9E3779B97F4A7C15ULL) >> shift_;
    while (slots_[i] != kEmpty) {
      i = (i + 1) & mask;
    }
    slots_[i] = v;
    used_.push_back(static_cast<std::uint32_t>(i));
  }
}

void MapTree::limitTo(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi)
{
  box_lo_ = lo;
  box_hi_ = hi;
  limited_ = true;
  std::array<std::size_t, 3> side{};
  for (unsigned a = 0; a < 3; ++a) {
    side[a] = hi[a] >= lo[a] ? std::size_t{hi[a]} - lo[a] + 1U : 0U;
  }
  box_side_ = {side[0], side[1]};
  const std::size_t voxels = side[0] * side[1] * side[2];
  settle();
  bounds_.clear();
  if (voxels > 0 && voxels <= kMaxBoundVoxels) {
    bounds_.assign((2 * voxels + 63) / 64, 0);
  }
  leaf_count_ = voxels > 0 && voxels <= kMaxLeafVoxels ? voxels : 0;
  resync();
}

void MapTree::resync()
{
  touched_.clear();  // updates of the tree before
  std::fill(bounds_.begin(), bounds_.end(), 0);
  leaves_.reset();
  unsettled_.reset();
  tree_in_box_ = true;
  changed_blocks_.clear();
  if (leaf_count_ == 0) {
    return;
  }
  changed_blocks_.assign(blockCount(box_lo_, box_hi_), 1);
  // Zeroed pages from the system, touched only where a voxel becomes known.
  leaves_.reset(static_cast<std::uint32_t*>(std::calloc(leaf_count_, sizeof(std::uint32_t))));
  unsettled_.reset(static_cast<std::uint64_t*>(std::calloc((leaf_count_ + 63) / 64, sizeof(std::uint64_t))));
  if (!leaves_ || !unsettled_) {
    throw std::bad_alloc();
  }
  // Every leaf's value on each of its voxels in the box (a pruned leaf stands for a cube).
  for (auto it = begin_leafs(), end = end_leafs(); it != end; ++it) {
    const octomap::OcTreeKey key = it.getKey();
    const unsigned span = 1U << (tree_depth - it.getDepth());
    std::array<unsigned, 3> from{};
    std::array<unsigned, 3> to{};
    bool inside = true;
    for (unsigned a = 0; a < 3; ++a) {
      const unsigned first = key[a] & ~(span - 1U);
      from[a] = std::max<unsigned>(first, box_lo_[a]);
      to[a] = std::min<unsigned>(first + span - 1U, box_hi_[a]);
      inside = inside && from[a] <= to[a];
      tree_in_box_ = tree_in_box_ && from[a] == first && to[a] == first + span - 1U;
    }
    if (!inside) {
      continue;
    }
    const std::uint32_t word = std::bit_cast<std::uint32_t>(it->getLogOdds()) ^ kUnknownLeaf;
    for (unsigned z = from[2]; z <= to[2]; ++z) {
      for (unsigned y = from[1]; y <= to[1]; ++y) {
        for (unsigned x = from[0]; x <= to[0]; ++x) {
          leaves_[boundIndex(octomap::OcTreeKey(static_cast<octomap::key_type>(x), static_cast<octomap::key_type>(y),
                                                static_cast<octomap::key_type>(z)))] = word;
        }
      }
    }
  }
}

void MapTree::takeChangedBlocks(std::vector<std::uint8_t>& changed)
{
  changed.assign(changed_blocks_.begin(), changed_blocks_.end());
  std::fill(changed_blocks_.begin(), changed_blocks_.end(), 0);
}

std::optional<VoxelBox> MapTree::voxelBox() const
{
  if (!leaves_ || !tree_in_box_) {
    return std::nullopt;
  }
  return VoxelBox{box_lo_, box_hi_, leaves_.get(), kUnknownLeaf, resolution, occ_prob_thres_log};
}

void MapTree::noteBounds(const octomap::OcTreeKey& key, float value)
{
  if (bounds_.empty() || !inBox(key)) {
    return;
  }
  const std::size_t bit = 2 * boundIndex(key);
  std::uint64_t& word = bounds_[bit >> 6];
  const unsigned shift = bit & 63;  // even: both of the voxel's bits lie in this word
  const std::uint64_t state = (value <= clamping_thres_min ? 1U : 0U) | (value >= clamping_thres_max ? 2U : 0U);
  word = (word & ~(std::uint64_t{3} << shift)) | (state << shift);
}

bool MapTree::beyondBox(const octomap::OcTreeKey& key, unsigned axis, int step) const
{
  // A ray's key moves along each axis one way only (its step's sign), or not at all.
  return limited_ && ((step >= 0 && key[axis] > box_hi_[axis]) || (step <= 0 && key[axis] < box_lo_[axis]));
}

void MapTree::freeAlongRay(const octomap::point3d& origin, const octomap::point3d& end)
{
  // OcTreeBaseImpl::computeRayKeys (Amanatides & Woo's DDA), expression for expression, so
  // that each ray crosses the same voxels; each goes into the scan's key set as it is
  // reached instead of into a KeyRay first, and the walk stops once the ray has left the
  // box for good (a sixth of the demo's ray steps lay beyond it).
  octomap::OcTreeKey key_origin, key_end;
  if (!coordToKeyChecked(origin, key_origin) || !coordToKeyChecked(end, key_end)) {
    return;  // OctoMap warns and leaves the ray out
  }
  if (key_origin == key_end) {
    return;  // the same cell: OctoMap's ray holds no key
  }
  octomap::point3d direction = (end - origin);
  const float length = static_cast<float>(direction.norm());
  direction /= length;
  int step[3];
  double t_max[3];
  double t_delta[3];
  octomap::OcTreeKey current_key = key_origin;
  // The floats promoted to double where OctoMap's expressions promote them.
  for (unsigned i = 0; i < 3; ++i) {
    const auto d = static_cast<double>(direction(i));
    if (d > 0.0) {
      step[i] = 1;
    } else if (d < 0.0) {
      step[i] = -1;
    } else {
      step[i] = 0;
    }
    if (step[i] != 0) {
      double voxel_border = keyToCoord(current_key[i]);
      voxel_border += static_cast<double>(static_cast<float>(step[i] * resolution * 0.5));
      t_max[i] = (voxel_border - static_cast<double>(origin(i))) / d;
      t_delta[i] = resolution / static_cast<double>(std::fabs(direction(i)));
    } else {
      t_max[i] = std::numeric_limits<double>::max();
      t_delta[i] = std::numeric_limits<double>::max();
    }
  }
  for (unsigned i = 0; i < 3; ++i) {
    if (beyondBox(current_key, i, step[i])) {
      return;  // no key of this ray lies in the box
    }
  }
  const auto visit = [&](const octomap::OcTreeKey& k) {
    if (inBox(k)) {
      keys_.insertFree(k);
    }
  };
  visit(current_key);
  // The walk's state in locals of its own (not arrays indexed by the axis): each step's
  // comparisons then read registers, not a store to memory just made.
  double t_x = t_max[0], t_y = t_max[1], t_z = t_max[2];
  const double d_x = t_delta[0], d_y = t_delta[1], d_z = t_delta[2];
  auto k_x = static_cast<octomap::key_type>(current_key[0]);
  auto k_y = static_cast<octomap::key_type>(current_key[1]);
  auto k_z = static_cast<octomap::key_type>(current_key[2]);
  const auto s_x = static_cast<octomap::key_type>(step[0]);
  const auto s_y = static_cast<octomap::key_type>(step[1]);
  const auto s_z = static_cast<octomap::key_type>(step[2]);
  while (true) {
    unsigned dim;
    if (t_x < t_y) {
      dim = t_x < t_z ? 0 : 2;
    } else {
      dim = t_y < t_z ? 1 : 2;
    }
    // A key moves by the step modulo 2^16, as OctoMap's key_type does.
    if (dim == 0) {
      t_x += d_x;
      k_x = static_cast<octomap::key_type>(k_x + s_x);
    } else if (dim == 1) {
      t_y += d_y;
      k_y = static_cast<octomap::key_type>(k_y + s_y);
    } else {
      t_z += d_z;
      k_z = static_cast<octomap::key_type>(k_z + s_z);
    }
    const octomap::OcTreeKey key(k_x, k_y, k_z);
    if (key == key_end) {
      return;
    }
    // The ray's length reached without reaching the end's cell (rounding): OctoMap stops too.
    if (std::min(std::min(t_x, t_y), t_z) > static_cast<double>(length)) {
      return;
    }
    if (beyondBox(key, dim, step[dim])) {
      return;  // every later key lies beyond the box too
    }
    visit(key);
  }
}

void MapTree::insertPointCloudTracked(const octomap::Pointcloud& cloud, const octomap::point3d& origin,
                                      double max_range, std::vector<KeyChange>& changes)
{
  reportPointCloud(cloud, origin, max_range, changes);
  settle();
}

void MapTree::reportPointCloud(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range,
                               std::vector<KeyChange>& changes)
{
  if (clamping_thres_min != bounds_min_ || clamping_thres_max != bounds_max_) {
    std::fill(bounds_.begin(), bounds_.end(), 0);  // bounds set since the bits were
    bounds_min_ = clamping_thres_min;
    bounds_max_ = clamping_thres_max;
  }
  collectKeys(cloud, origin, max_range);
  // Each voxel is updated once per scan and only its own update changes its value, so the
  // order of the updates changes neither the leaves nor the pruning the tree ends with.
  const bool bounded = !bounds_.empty();  // every key of the set lies in the box then
  const bool kept = leaves_ != nullptr;
  if (!kept) {
    settle();  // none pending: the updates go to the tree at once, from a path of none
  }
  keys_.forEach([&](const octomap::OcTreeKey& key, bool occupied) {
    if (bounded && atBound(boundIndex(key), occupied)) {
      ++skipped_at_bounds_;
      return;
    }
    if (kept) {
      reportUpdate(key, occupied, changes);
    } else if (const std::optional<bool> after = updateTracked(key, occupied)) {
      changes.push_back({key, *after});
    }
  });
}

void MapTree::reportUpdate(const octomap::OcTreeKey& key, bool occupied, std::vector<KeyChange>& changes)
{
  // What updateTracked does to the voxel's leaf, on a copy of its value: OctoMap's early
  // abort at the clamping bound, its addition and clamping, and the change it makes.
  std::uint32_t& word = leaves_[boundIndex(key)];
  const bool known = word != 0;
  const float delta = occupied ? prob_hit_log : prob_miss_log;
  octomap::OcTreeNode& leaf = scratch_leaf_;
  leaf.setLogOdds(known ? std::bit_cast<float>(word ^ kUnknownLeaf) : 0.0F);  // a created voxel starts at 0
  if (known) {
    const float value = leaf.getLogOdds();
    if ((delta >= 0 && value >= clamping_thres_max) || (delta <= 0 && value <= clamping_thres_min)) {
      noteBounds(key, value);
      return;
    }
  }
  const bool occupied_before = known && isNodeOccupied(leaf);
  OccupancyOcTreeBase::updateNodeLogOdds(&leaf, delta);  // OctoMap's, called directly
  word = std::bit_cast<std::uint32_t>(leaf.getLogOdds()) ^ kUnknownLeaf;
  changed_blocks_[blockOf(box_lo_, box_hi_, key)] = 1;
  noteBounds(key, leaf.getLogOdds());
  const std::size_t voxel = boundIndex(key);
  if (std::uint64_t& bits = unsettled_[voxel >> 6]; (bits & (std::uint64_t{1} << (voxel & 63))) == 0) {
    bits |= std::uint64_t{1} << (voxel & 63);
    touched_.push_back(key);
  }
  const bool occupied_after = isNodeOccupied(leaf);
  if (!known || occupied_before != occupied_after) {
    changes.push_back({key, occupied_after});
  }
}

void MapTree::collectKeys(const octomap::Pointcloud& cloud, const octomap::point3d& origin, double max_range)
{
  // OccupancyOcTreeBase::computeUpdate without a bounding box, expression for expression,
  // so that every ray ends in the same voxel.
  // Every key of the scan lies within the range (and a voxel of rounding) of the origin's.
  octomap::OcTreeKey centre;
  const double reach = std::ceil(max_range / resolution) + 2.0;
  if (max_range >= 0.0 && reach <= ScanKeySet::kMaxWindowRadius && coordToKeyChecked(origin, centre)) {
    keys_.clear(centre, static_cast<unsigned>(reach));
  } else {
    keys_.clear();
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const octomap::point3d& p = cloud[i];
    // A point beyond range clears space up to the range only; its end is not a hit.
    const bool hit = max_range < 0.0 || (p - origin).norm() <= max_range;
    const octomap::point3d end = hit ? p : origin + (p - origin).normalized() * static_cast<float>(max_range);
    freeAlongRay(origin, end);
    octomap::OcTreeKey key;
    if (hit && coordToKeyChecked(p, key) && inBox(key)) {
      keys_.insertOccupied(key);
    }
  }
}

std::optional<bool> MapTree::updateTracked(const octomap::OcTreeKey& key, bool occupied)
{
  const float delta = occupied ? prob_hit_log : prob_miss_log;
  // OcTree::updateNode's early abort: the voxel (or the pruned node holding it) is already
  // at the clamping bound the update pushes towards; nothing changes.
  const auto at_bound = [&](float value) {
    if ((delta >= 0 && value >= clamping_thres_max) || (delta <= 0 && value <= clamping_thres_min)) {
      noteBounds(key, value);
      return true;
    }
    return false;
  };
  return descendAndUpdate(key, at_bound, [&](octomap::OcTreeNode* leaf) {
    updateNodeLogOdds(leaf, delta);
    if (leaves_ == nullptr) {
      noteBounds(key, leaf->getLogOdds());  // else reportUpdate noted it, from the same value
    }
  });
}

template <class Unchanged, class Update>
std::optional<bool> MapTree::descendAndUpdate(const octomap::OcTreeKey& key, Unchanged unchanged, Update update)
{
  auto& path = path_;   // root at 0, the voxel at tree_depth (16)
  bool created = false;  // path[depth] was created by this update
  unsigned depth = 0;
  if (root == nullptr) {
    root = new octomap::OcTreeNode();
    ++tree_size;
    created = true;
  } else if (path_valid_ >= 0) {
    // The levels whose child indices agree with the last key's lead to the same nodes.
    const unsigned differ = static_cast<unsigned>((key[0] ^ path_key_[0]) | (key[1] ^ path_key_[1]) | (key[2] ^ path_key_[2]));
    const auto common = static_cast<unsigned>(std::countl_zero(static_cast<std::uint16_t>(differ)));
    depth = std::min({common, static_cast<unsigned>(path_valid_), static_cast<unsigned>(tree_depth)});
  }
  path[0] = root;
  path_key_ = key;
  // As far as the key's path exists: where OcTree::search stops.
  while (depth < tree_depth) {
    const unsigned pos = octomap::computeChildIdx(key, static_cast<int>(tree_depth - 1 - depth));
    if (!nodeChildExists(path[depth], pos)) {
      break;
    }
    path[depth + 1] = getNodeChild(path[depth], pos);
    ++depth;
  }
  // path[0 ... existed] were in the tree before this update, with their values then.
  const unsigned existed = created ? 0 : depth;
  // A voxel in the tree (alone, or in a pruned node) the update leaves as it is.
  if (!created && (depth == tree_depth || !nodeHasChildren(path[depth])) && unchanged(path[depth]->getLogOdds())) {
    path_valid_ = static_cast<int>(depth);
    return std::nullopt;
  }
  // The rest of the way down, as updateNodeRecurs goes: a pruned node is expanded (its
  // children inherit its value), a missing child of an inner node is created unknown.
  for (; depth < tree_depth; ++depth) {
    octomap::OcTreeNode* node = path[depth];
    const unsigned pos = octomap::computeChildIdx(key, static_cast<int>(tree_depth - 1 - depth));
    bool child_created = false;
    if (!nodeChildExists(node, pos)) {
      if (!nodeHasChildren(node) && !created) {
        expandNode(node);
      } else {
        createNodeChild(node, pos);
        child_created = true;
      }
    }
    path[depth + 1] = getNodeChild(node, pos);
    created = child_created;
  }
  octomap::OcTreeNode* leaf = path[tree_depth];
  const bool occupied_before = !created && isNodeOccupied(leaf);
  update(leaf);
  const bool occupied_after = isNodeOccupied(leaf);
  const bool changed = created || occupied_before != occupied_after;
  // Back up: prune where the eight children agree, else refresh the inner node's value.
  // OctoMap goes on to the root; it can stop at an inner node that stays inner and keeps the
  // value it had, because nothing above it changes then: its parent's children keep their
  // values, and no ancestor can be pruned while one of its children has children.
  path_valid_ = static_cast<int>(tree_depth);
  for (int d = static_cast<int>(tree_depth) - 1; d >= 0; --d) {
    octomap::OcTreeNode* node = path[static_cast<std::size_t>(d)];
    if (pruneNode(node)) {
      path_valid_ = d;  // its children are gone
      continue;
    }
    const float before = node->getLogOdds();
    node->updateOccupancyChildren();
    if (static_cast<unsigned>(d) <= existed && node->getLogOdds() == before) {
      break;
    }
  }
  return changed ? std::optional<bool>(occupied_after) : std::nullopt;
}

void MapTree::settle() { settle(detachUnsettled()); }

std::vector<MapTree::VoxelValue> MapTree::detachUnsettled()
{
  std::vector<VoxelValue> voxels;
  voxels.reserve(touched_.size());
  for (const octomap::OcTreeKey& key : touched_) {
    const std::size_t voxel = boundIndex(key);
    unsettled_[voxel >> 6] &= ~(std::uint64_t{1} << (voxel & 63));
    voxels.push_back({key, std::bit_cast<float>(leaves_[voxel] ^ kUnknownLeaf)});
  }
  touched_.clear();
  return voxels;
}

void MapTree::settle(const std::vector<VoxelValue>& voxels)
{
  // Each voxel set once to its value: OctoMap's tree is pruned wherever eight sibling leaves
  // agree after every update, so the tree its updates build depends only on the voxels'
  // values, not on the order or the steps they came in.
  path_valid_ = -1;
  for (const VoxelValue& v : voxels) {
    descendAndUpdate(
        v.key, [&](float before) { return before == v.log_odds; },
        [&](octomap::OcTreeNode* leaf) { leaf->setLogOdds(v.log_odds); });
  }
}

}  // namespace quad::mapping
