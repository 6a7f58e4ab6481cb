// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/map_follower.hpp"

#include <algorithm>

namespace quad::mapping {

MapFollower::MapFollower(double resolution, std::size_t max_kept)
    : resolution_(resolution), max_kept_(max_kept), held_(resolution)
{
}

std::vector<VoxelChange> MapFollower::update(std::uint64_t seq, std::vector<VoxelChange> changes, bool* bad)
{
  if (bad != nullptr) {
    *bad = false;
  }
  if (seq == 1 && applied_seq_ > 1) {
    ++restarts_;
    std::vector<VoxelChange> forgotten;
    for (const auto& c : held_.contents()) {
      forgotten.push_back({c.index, VoxelState::kUnknown});
    }
    held_ = VoxelMap(resolution_);
    applied_seq_ = 0;
    gap_open_ = false;
    gap_end_ = 0;
    since_gap_.clear();
    kept_.reset();
    auto fresh = update(seq, std::move(changes), bad);
    forgotten.insert(forgotten.end(), fresh.begin(), fresh.end());
    return forgotten;
  }
  if (seq <= applied_seq_) {
    return {};  // in a snapshot already applied
  }
  if (seq != applied_seq_ + 1) {
    ++gaps_;
    gap_open_ = true;
    gap_end_ = seq - 1;
  }
  held_.apply(changes);
  applied_seq_ = seq;
  if (gap_open_) {
    since_gap_.emplace_back(seq, changes);
    if (since_gap_.size() > max_kept_) {
      gap_end_ = std::max(gap_end_, since_gap_.front().first);
      since_gap_.pop_front();
    }
  }
  if (kept_ && gap_open_ && kept_->first >= gap_end_) {
    auto kept = std::move(*kept_);
    kept_.reset();
    if (const auto diff = fill(kept.first, kept.second, bad)) {
      changes.insert(changes.end(), diff->begin(), diff->end());
    }
  } else if (kept_ && kept_->first <= applied_seq_) {
    kept_.reset();  // the updates reached it: not needed
  }
  return changes;
}

std::optional<std::vector<VoxelChange>> MapFollower::snapshot(std::uint64_t seq, const std::vector<std::uint8_t>& bytes,
                                                              bool* bad)
{
  if (bad != nullptr) {
    *bad = false;
  }
  if (!gap_open_ && applied_seq_ != 0) {
    if (seq > applied_seq_ && (!kept_ || seq > kept_->first)) {
      kept_.emplace(seq, bytes);
    }
    return std::nullopt;  // nothing missing (yet)
  }
  if (seq < gap_end_) {
    return std::nullopt;  // too old to fill the hole
  }
  return fill(seq, bytes, bad);
}

std::optional<std::vector<VoxelChange>> MapFollower::fill(std::uint64_t seq, const std::vector<std::uint8_t>& bytes,
                                                          bool* bad)
{
  VoxelMap map(resolution_);
  if (!map.applySnapshot(bytes)) {
    if (bad != nullptr) {
      *bad = true;
    }
    return std::nullopt;
  }
  replayed_ = 0;
  for (const auto& [s, changes] : since_gap_) {
    if (s > seq) {
      map.apply(changes);
      ++replayed_;
    }
  }
  // Whatever differs from what is held: voxels the map knows, and held ones it does not.
  std::vector<VoxelChange> diff;
  for (const auto& c : map.contents()) {
    if (held_.classify(c.index) != c.state) {
      diff.push_back(c);
    }
  }
  for (const auto& c : held_.contents()) {
    if (map.classify(c.index) == VoxelState::kUnknown) {
      diff.push_back({c.index, VoxelState::kUnknown});
    }
  }
  held_.apply(diff);
  applied_seq_ = std::max(applied_seq_, seq);
  gap_open_ = false;
  since_gap_.clear();
  if (kept_ && kept_->first <= applied_seq_) {
    kept_.reset();
  }
  return diff;
}

}  // namespace quad::mapping
