// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/voxel_map.hpp"

#include <algorithm>
#include <utility>

#include "quad/mapping/mapper.hpp"

namespace quad::mapping {

namespace {

using geometry::VoxelTable;

// A voxel's state is its table state: none is unknown.
static_assert(static_cast<int>(VoxelState::kUnknown) == 0);

std::uint64_t pack(const VoxelChange& c) { return VoxelTable::wordOf(c.index, static_cast<std::uint8_t>(c.state)); }

VoxelChange unpack(std::uint64_t word)
{
  return {VoxelTable::indexOf(word), static_cast<VoxelState>(VoxelTable::stateOf(word))};
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
  if (!std::all_of(voxels.begin(), voxels.end(), [](const VoxelChange& c) { return VoxelTable::holds(c.index); })) {
    std::sort(voxels.begin(), voxels.end(), [](const VoxelChange& a, const VoxelChange& b) { return indexLess(a.index, b.index); });
    return;
  }
  std::vector<std::uint64_t> words(voxels.size());
  std::transform(voxels.begin(), voxels.end(), words.begin(), pack);
  sortWords(words);
  std::transform(words.begin(), words.end(), voxels.begin(), unpack);
}

bool VoxelMap::applySnapshot(const std::vector<std::uint8_t>& bytes)
{
  const auto cells = classificationOf(bytes, resolution_);
  if (!cells) {
    return false;
  }
  voxels_.clear();
  voxels_.reserve(cells->size());
  apply(*cells);
  return true;
}

void VoxelMap::apply(const std::vector<VoxelChange>& changes)
{
  for (const auto& c : changes) {
    voxels_.set(c.index, static_cast<std::uint8_t>(c.state));  // unknown: let go
  }
}

VoxelState VoxelMap::classify(const VoxelIndex& index) const { return static_cast<VoxelState>(voxels_.get(index)); }

std::vector<VoxelChange> VoxelMap::contents() const
{
  std::vector<std::uint64_t> words = voxels_.words();
  sortWords(words);
  std::vector<VoxelChange> out(words.size());
  std::transform(words.begin(), words.end(), out.begin(), unpack);
  return out;
}

}  // namespace quad::mapping
