// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A set of voxels with a small state each (1, 2 or 3 of 2 bits; 0 is none), in one flat
/// table: a word per voxel, linear probing. A map's consumers hold millions of voxels and look
/// each up as a change set arrives: a node-based hash map spent most of their time in its
/// nodes.

#include <cstdint>
#include <vector>

#include "quad/geometry/grid.hpp"

namespace quad::geometry {

class VoxelTable {
public:
  /// A voxel's coordinates offset by 2^19 in 20 bits each, x highest (the words of a set
  /// sort as its indices do, x, then y, then z), then its state in the lowest two bits.
  static constexpr int kAxisBits = 20;

  /// True when `index` can be held: within 2^19 of the origin on every axis (an OctoMap's
  /// reach is 2^15).
  static bool holds(const VoxelIndex& index)
  {
    return (index.array() >= -kOffset).all() && (index.array() < kOffset).all();
  }
  /// The voxel's state; 0 when not held.
  std::uint8_t get(const VoxelIndex& index) const
  {
    if (size_ == 0 || !holds(index)) {
      return 0;
    }
    const std::uint64_t word = slots_[find(keyOf(index))];
    return word == kEmpty ? 0 : static_cast<std::uint8_t>(word & 3U);
  }
  /// Holds the voxel with `state` (1 to 3), or lets it go with 0. Indices holds() refuses are
  /// left out.
  void set(const VoxelIndex& index, std::uint8_t state);
  void clear();
  /// Room for `voxels` without growing.
  void reserve(std::size_t voxels);
  std::size_t size() const { return size_; }

  /// Every voxel held as a word (as described at kAxisBits), in no order.
  std::vector<std::uint64_t> words() const;
  static VoxelIndex indexOf(std::uint64_t word);
  static std::uint8_t stateOf(std::uint64_t word) { return static_cast<std::uint8_t>(word & 3U); }
  static std::uint64_t wordOf(const VoxelIndex& index, std::uint8_t state) { return (keyOf(index) << 2) | state; }

private:
  static constexpr int kOffset = 1 << (kAxisBits - 1);
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // state 3 of no voxel's key

  static std::uint64_t keyOf(const VoxelIndex& index)
  {
    const auto axis = [](int v) { return static_cast<std::uint64_t>(v + kOffset); };
    return (axis(index.x()) << (2 * kAxisBits)) | (axis(index.y()) << kAxisBits) | axis(index.z());
  }
  /// Where a search for `key` starts (Fibonacci hashing: the key times 2^64/φ, middle bits).
  static std::size_t homeOf(std::uint64_t key, std::size_t mask)
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 32) & mask;
  }
  /// The slot holding `key`, or the empty one where it would go.
  std::size_t find(std::uint64_t key) const
  {
    const std::size_t mask = slots_.size() - 1;
    std::size_t slot = homeOf(key, mask);
    while (slots_[slot] != kEmpty && (slots_[slot] >> 2) != key) {
      slot = (slot + 1) & mask;
    }
    return slot;
  }
  void erase(std::uint64_t key);
  /// To `slots` slots (a power of two, more than twice the voxels held).
  void rehash(std::size_t slots);

  std::vector<std::uint64_t> slots_;
  std::size_t size_ = 0;
};

}  // namespace quad::geometry
