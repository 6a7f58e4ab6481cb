// SPDX-License-Identifier: BSD-3-Clause
#include "quad/geometry/voxel_table.hpp"

#include <algorithm>
#include <bit>
#include <iterator>

namespace quad::geometry {

namespace {
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << VoxelTable::kAxisBits) - 1;
constexpr std::size_t kFewestSlots = 64;
}  // namespace

void VoxelTable::set(const VoxelIndex& index, std::uint8_t state)
{
  if (!holds(index)) {
    return;
  }
  const std::uint64_t key = keyOf(index);
  if (state == 0) {
    erase(key);
    return;
  }
  if (2 * (size_ + 1) > slots_.size()) {
    rehash(std::max(kFewestSlots, 2 * slots_.size()));
  }
  std::uint64_t& slot = slots_[find(key)];
  size_ += slot == kEmpty ? 1U : 0U;
  slot = (key << 2) | state;
}

void VoxelTable::clear()
{
  std::fill(slots_.begin(), slots_.end(), kEmpty);
  size_ = 0;
}

void VoxelTable::reserve(std::size_t voxels)
{
  const std::size_t slots = std::bit_ceil(std::max(kFewestSlots, 2 * voxels + 1));
  if (slots > slots_.size()) {
    rehash(slots);
  }
}

std::vector<std::uint64_t> VoxelTable::words() const
{
  std::vector<std::uint64_t> out;
  out.reserve(size_);
  std::copy_if(slots_.begin(), slots_.end(), std::back_inserter(out), [](std::uint64_t w) { return w != kEmpty; });
  return out;
}

VoxelIndex VoxelTable::indexOf(std::uint64_t word)
{
  const std::uint64_t key = word >> 2;
  const auto axis = [&](int shift) { return static_cast<int>((key >> shift) & kAxisMask) - kOffset; };
  return {axis(2 * kAxisBits), axis(kAxisBits), axis(0)};
}

void VoxelTable::erase(std::uint64_t key)
{
  if (size_ == 0) {
    return;
  }
  const std::size_t mask = slots_.size() - 1;
  std::size_t hole = find(key);
  if (slots_[hole] == kEmpty) {
    return;
  }
  --size_;
  // Backward shift: a later word of the run moves into the hole unless its home slot lies
  // cyclically in (hole, its slot], where a search for it starts past the hole anyway.
  for (std::size_t next = (hole + 1) & mask; slots_[next] != kEmpty; next = (next + 1) & mask) {
    const std::size_t home = homeOf(slots_[next] >> 2, mask);
    const bool stays = hole <= next ? (hole < home && home <= next) : (hole < home || home <= next);
    if (!stays) {
      slots_[hole] = slots_[next];
      hole = next;
    }
  }
  slots_[hole] = kEmpty;
}

void VoxelTable::rehash(std::size_t slots)
{
  std::vector<std::uint64_t> old(slots, kEmpty);
  old.swap(slots_);
  for (const std::uint64_t word : old) {
    if (word != kEmpty) {
      slots_[find(word >> 2)] = word;
    }
  }
}

}  // namespace quad::geometry
