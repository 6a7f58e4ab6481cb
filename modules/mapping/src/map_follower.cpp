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

namespace {

bool byIndex(const VoxelChange& a, const VoxelChange& b) { return indexLess(a.index, b.index); }

/// `base` (sorted by index) with `changes` applied in their order: sorted, unknown dropped.
std::vector<VoxelChange> overlay(const std::vector<VoxelChange>& base, std::vector<VoxelChange> changes)
{
  std::stable_sort(changes.begin(), changes.end(), byIndex);
  std::vector<VoxelChange> out;
  out.reserve(base.size() + changes.size());
  auto b = base.begin();
  for (auto c = changes.begin(); c != changes.end(); ++c) {
    if (std::next(c) != changes.end() && !byIndex(*c, *std::next(c))) {
      continue;  // a later change of the same voxel wins
    }
    for (; b != base.end() && byIndex(*b, *c); ++b) {
      out.push_back(*b);
    }
    if (b != base.end() && !byIndex(*c, *b)) {
      ++b;  // replaced
    }
    if (c->state != VoxelState::kUnknown) {
      out.push_back(*c);
    }
  }
  out.insert(out.end(), b, base.end());
  return out;
}

/// The changes that turn `from` into `to` (both sorted by index, no unknown): `to`'s voxels
/// that `from` classifies otherwise, and `from`'s that `to` does not know, as unknown.
std::vector<VoxelChange> difference(const std::vector<VoxelChange>& from, const std::vector<VoxelChange>& to)
{
  std::vector<VoxelChange> out;
  auto f = from.begin();
  auto t = to.begin();
  while (f != from.end() || t != to.end()) {
    if (t == to.end() || (f != from.end() && byIndex(*f, *t))) {
      out.push_back({f->index, VoxelState::kUnknown});
      ++f;
    } else if (f == from.end() || byIndex(*t, *f)) {
      out.push_back(*t);
      ++t;
    } else {
      if (f->state != t->state) {
        out.push_back(*t);
      }
      ++f;
      ++t;
    }
  }
  return out;
}

}  // namespace

std::optional<std::vector<VoxelChange>> MapFollower::fill(std::uint64_t seq, const std::vector<std::uint8_t>& bytes,
                                                          bool* bad)
{
  // Sorted sequences merged, not hash lookups: a planner's catch-up compares whole maps
  // (a million voxels), and it hovers while it does.
  auto map = classificationOf(bytes, resolution_);
  if (!map) {
    if (bad != nullptr) {
      *bad = true;
    }
    return std::nullopt;
  }
  replayed_ = 0;
  std::vector<VoxelChange> later;
  for (const auto& [s, changes] : since_gap_) {
    if (s > seq) {
      later.insert(later.end(), changes.begin(), changes.end());
      ++replayed_;
    }
  }
  if (!later.empty()) {
    *map = overlay(*map, std::move(later));
  }
  auto diff = difference(held_.contents(), *map);
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
