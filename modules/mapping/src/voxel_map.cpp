// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/voxel_map.hpp"

#include <algorithm>
#include <iterator>
#include <optional>
#include <utility>

#include "quad/mapping/mapper.hpp"

namespace quad::mapping {

namespace {

// A voxel in one word: each coordinate offset by 2^19 in 20 bits, x highest (so the words'
// order is indexLess), then the state in the lowest two bits.
constexpr int kBits = 20;
constexpr int kOffset = 1 << (kBits - 1);
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << kBits) - 1;
constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // state 3: no voxel's

bool packable(const VoxelIndex& i)
{
  return (i.array() >= -kOffset).all() && (i.array() < kOffset).all();
}

std::uint64_t keyOf(const VoxelIndex& i)
{
  const auto axis = [](int v) { return static_cast<std::uint64_t>(v + kOffset); };
  return (axis(i.x()) << (2 * kBits)) | (axis(i.y()) << kBits) | axis(i.z());
}

std::uint64_t pack(std::uint64_t key, VoxelState state) { return (key << 2) | static_cast<std::uint64_t>(state); }
std::uint64_t keyOfWord(std::uint64_t word) { return word >> 2; }

/// Where a search for `key` starts (Fibonacci hashing: the key times 2^64/φ, middle bits).
std::size_t homeOf(std::uint64_t key, std::size_t mask)
{
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 32) & mask;
}

VoxelChange unpack(std::uint64_t word)
{
  const std::uint64_t key = keyOfWord(word);
  const auto axis = [&](int shift) { return static_cast<int>((key >> shift) & kAxisMask) - kOffset; };
  return {VoxelIndex(axis(2 * kBits), axis(kBits), axis(0)), static_cast<VoxelState>(word & 3U)};
}

/// Sorts packed voxels: least significant digit first, 11 bits a pass, a pass skipped where
/// every word has the same digit (the high axis bits, in a map of a few hundred metres).
/// A million voxels take a tenth of std::sort's time.
void sortWords(std::vector<std::uint64_t>& words)
{
  constexpr int kDigit = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigit;
  if (words.size() < 4096) {
    std::sort(words.begin(), words.end());
    return;
  }
  std::vector<std::uint64_t> buffer(words.size());
  std::vector<std::size_t> start(kBuckets);
  for (int shift = 0; shift < 64; shift += kDigit) {
    std::fill(start.begin(), start.end(), 0);
    for (const std::uint64_t w : words) {
      ++start[(w >> shift) & (kBuckets - 1)];
    }
    if (std::find(start.begin(), start.end(), words.size()) != start.end()) {
      continue;
    }
    std::size_t sum = 0;
    for (auto& s : start) {
      sum += std::exchange(s, sum);
    }
    for (const std::uint64_t w : words) {
      buffer[start[(w >> shift) & (kBuckets - 1)]++] = w;
    }
    words.swap(buffer);
  }
}

}  // namespace

void sortByIndex(std::vector<VoxelChange>& voxels)
{
  // Integers compare faster than index triples: a snapshot's million voxels are sorted on
  // every catch-up.
  if (!std::all_of(voxels.begin(), voxels.end(), [](const VoxelChange& c) { return packable(c.index); })) {
    std::sort(voxels.begin(), voxels.end(), [](const VoxelChange& a, const VoxelChange& b) { return indexLess(a.index, b.index); });
    return;
  }
  std::vector<std::uint64_t> words(voxels.size());
  std::transform(voxels.begin(), voxels.end(), words.begin(), [](const VoxelChange& c) { return pack(keyOf(c.index), c.state); });
  sortWords(words);
  std::transform(words.begin(), words.end(), voxels.begin(), unpack);
}

bool VoxelMap::applySnapshot(const std::vector<std::uint8_t>& bytes)
{
  const auto cells = classificationOf(bytes, resolution_);
  if (!cells) {
    return false;
  }
  slots_.clear();
  size_ = 0;
  apply(*cells);
  return true;
}

void VoxelMap::apply(const std::vector<VoxelChange>& changes)
{
  for (const auto& c : changes) {
    if (!packable(c.index)) {
      continue;
    }
    if (c.state == VoxelState::kUnknown) {
      erase(keyOf(c.index));
    } else {
      set(keyOf(c.index), c.state);
    }
  }
}

VoxelState VoxelMap::classify(const VoxelIndex& index) const
{
  if (size_ == 0 || !packable(index)) {
    return VoxelState::kUnknown;
  }
  const std::uint64_t word = slots_[find(keyOf(index))];
  return word == kEmpty ? VoxelState::kUnknown : unpack(word).state;
}

std::vector<VoxelChange> VoxelMap::contents() const
{
  std::vector<std::uint64_t> words;
  words.reserve(size_);
  std::copy_if(slots_.begin(), slots_.end(), std::back_inserter(words), [](std::uint64_t w) { return w != kEmpty; });
  sortWords(words);
  std::vector<VoxelChange> out(words.size());
  std::transform(words.begin(), words.end(), out.begin(), unpack);
  return out;
}

std::size_t VoxelMap::find(std::uint64_t key) const
{
  const std::size_t mask = slots_.size() - 1;
  std::size_t slot = homeOf(key, mask);
  while (slots_[slot] != kEmpty && keyOfWord(slots_[slot]) != key) {
    slot = (slot + 1) & mask;
  }
  return slot;
}

void VoxelMap::set(std::uint64_t key, VoxelState state)
{
  if (2 * (size_ + 1) > slots_.size()) {
    grow();
  }
  std::uint64_t& slot = slots_[find(key)];
  size_ += slot == kEmpty ? 1U : 0U;
  slot = pack(key, state);
}

void VoxelMap::erase(std::uint64_t key)
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
    const std::size_t home = homeOf(keyOfWord(slots_[next]), mask);
    const bool stays = hole <= next ? (hole < home && home <= next) : (hole < home || home <= next);
    if (!stays) {
      slots_[hole] = slots_[next];
      hole = next;
    }
  }
  slots_[hole] = kEmpty;
}

void VoxelMap::grow()
{
  std::vector<std::uint64_t> old(std::max<std::size_t>(64, 2 * slots_.size()), kEmpty);
  old.swap(slots_);
  for (const std::uint64_t word : old) {
    if (word != kEmpty) {
      slots_[find(keyOfWord(word))] = word;
    }
  }
}

}  // namespace quad::mapping
