// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The consumer's side of the mapper's numbered change sets and snapshots (the planner's):
/// applies updates in order, notices a gap (a late join, a missed update), and fills it with
/// the first snapshot that covers it, brought up to date with the updates received after it
/// (a snapshot travels slower than the update of its own number). What it holds then equals
/// the mapper's classification.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include "quad/mapping/mapper.hpp"

namespace quad::mapping {

class MapFollower {
public:
  /// `max_kept`: updates kept while a gap is open (the oldest go first; a snapshot must then
  /// be at least as new as the newest one dropped).
  explicit MapFollower(double resolution, std::size_t max_kept = 256);

  /// Update `seq` with its changes; returns the changes to apply downstream (none when the
  /// update was already covered by a snapshot). Update 1 after later ones is a mapper that
  /// started again with an empty map (no checkpoint to resume from): what was held is gone
  /// from the map, so it is returned as unknown, and the new numbering is followed. When it opens a gap that a kept snapshot
  /// covers (see snapshot()), the gap is filled at once: the changes returned then bring
  /// the consumer to that snapshot too (`bad` as for snapshot()).
  std::vector<VoxelChange> update(std::uint64_t seq, std::vector<VoxelChange> changes, bool* bad = nullptr);

  /// A snapshot taken at update `seq`, as OctoMap bytes. When it fills the open gap (or
  /// nothing was received yet) returns the changes that bring what is held to it; nothing
  /// otherwise. Bytes that are not a map of this resolution: `bad` is set, nothing returned.
  /// A snapshot newer than every update held, with no gap open, is kept undecoded (decoding
  /// a large map costs a few hundred ms) until the updates reach it, or until a gap it
  /// covers opens: a reader that matched mid-stream may never get the update or two sent
  /// around its match, and the mapper's fresh snapshots may arrive before the hole shows.
  std::optional<std::vector<VoxelChange>> snapshot(std::uint64_t seq, const std::vector<std::uint8_t>& bytes,
                                                   bool* bad = nullptr);

  /// True while an update is missing that no snapshot filled yet.
  bool gapOpen() const { return gap_open_; }
  /// The newest update held (0: none yet).
  std::uint64_t appliedSeq() const { return applied_seq_; }
  /// Gaps seen so far.
  std::uint64_t gaps() const { return gaps_; }
  /// Mappers seen starting again from an empty map.
  std::uint64_t restarts() const { return restarts_; }
  /// Updates a snapshot's catch-up re-applied on top of it, last time.
  std::size_t replayed() const { return replayed_; }
  const VoxelMap& held() const { return held_; }

private:
  /// Fills the open gap from a snapshot (see snapshot()); nothing when the bytes are bad.
  std::optional<std::vector<VoxelChange>> fill(std::uint64_t seq, const std::vector<std::uint8_t>& bytes, bool* bad);

  double resolution_;
  std::size_t max_kept_;
  VoxelMap held_;
  std::uint64_t applied_seq_ = 0;
  bool gap_open_ = false;
  std::uint64_t gap_end_ = 0;  // the last update missed: snapshots from it on fill the gap
  std::deque<std::pair<std::uint64_t, std::vector<VoxelChange>>> since_gap_;
  std::uint64_t gaps_ = 0;
  std::uint64_t restarts_ = 0;
  std::size_t replayed_ = 0;
  std::optional<std::pair<std::uint64_t, std::vector<std::uint8_t>>> kept_;  // a snapshot ahead of the updates
};

}  // namespace quad::mapping
