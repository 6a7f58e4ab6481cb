// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A priority queue of cells in buckets of keys: bucket b holds the keys whose level (a
/// non-decreasing function of the key, such as its first component over a width) is b, and
/// only the lowest bucket that holds anything is kept in order, as an IndexedHeap. Changing
/// the key of a cell that sits above it, or moving a cell from one bucket to another, is an
/// append or a swap with the last entry, whatever the size of the queue.
///
/// D* Lite's queue lives across replans and holds the whole frontier of its search, thousands
/// of cells, while every replan takes out only those near the top; as the start moves, the
/// cells it takes out mostly get a later key and go back in (Koenig & Likhachev's key update).
/// In one heap each of those is a sift through all of it; here it is a move to a later bucket.
///
/// Keys that go out of date all at once (D* Lite's, when the start moves) are brought up to
/// date a bucket at a time: after keysAged(), top(fresh) gives each entry of the lowest bucket
/// its key now before it orders that bucket, and the entries whose key left it go to their
/// own bucket, without a sift. Keys may only rise with age; a bucket is refreshed once an age.
///
/// Cells come out as from one heap over every key, with one difference: two keys that the
/// keys' order calls equivalent (Key may compare with a tolerance) but that lie in different
/// buckets come out by bucket.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "quad/planning/indexed_heap.hpp"

namespace quad::planning {

/// Where a cell sits in a BucketQueue: its bucket (kNotQueued when it is not queued) and its
/// place in that bucket's heap.
struct QueuePlace {
  std::uint32_t bucket = kNotQueued;
  std::uint32_t index = kNotQueued;
};

/// PlaceOf is callable as `QueuePlace& place(std::int64_t cell)`, the caller's record of the
/// cell's place; LevelOf as `std::uint32_t level(const Key&)`, non-decreasing in the key's
/// order and below kNotQueued. Equal keys come out by cell number, smallest first.
template <typename Key, typename PlaceOf, typename LevelOf>
class BucketQueue {
  /// A bucket's heap reaches the index in the cell's place.
  struct IndexOf {
    PlaceOf place;
    std::uint32_t& operator()(std::int64_t cell) const { return place(cell).index; }
  };
  using Bucket = IndexedHeap<Key, IndexOf>;

public:
  using Cell = std::int64_t;
  using Entry = typename Bucket::Entry;

  BucketQueue(PlaceOf place, LevelOf level) : place_(std::move(place)), level_(std::move(level)) {}

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  /// The least entry; the queue must not be empty.
  const Entry& top() { return buckets_[lowest()].top(); }

  /// The least entry after the keys up to it were brought up to date: `fresh(entry)` gives an
  /// entry's key now, not lower than the one it was queued with. The queue must not be empty.
  template <typename Fresh>
  const Entry& top(Fresh&& fresh)
  {
    for (;;) {
      const std::uint32_t b = lowest();
      if (ages_[b] == age_) {
        return buckets_[b].top();
      }
      ages_[b] = age_;
      const std::vector<Entry> held = buckets_[b].take();
      for (const Entry& e : held) {
        place_(e.cell).bucket = kNotQueued;
      }
      size_ -= held.size();
      for (const Entry& e : held) {
        set(e.cell, fresh(e));
      }
    }
  }

  /// Every queued key may be out of date now (and not lower than it was).
  void keysAged() { ++age_; }

  /// Queues `cell` with `key`, or changes its key when it is queued already.
  void set(Cell cell, const Key& key)
  {
    const std::uint32_t b = level_(key);
    QueuePlace& at = place_(cell);
    if (at.bucket != b) {
      if (at.bucket == kNotQueued) {
        ++size_;
      } else {
        buckets_[at.bucket].remove(cell, at.index);
      }
      if (b >= buckets_.size()) {
        buckets_.resize(b + std::size_t{1}, Bucket(IndexOf{place_}));
        ages_.resize(buckets_.size(), age_);
      }
      if (buckets_[b].empty()) {
        ages_[b] = age_;  // what it will hold is up to date
      }
      at.bucket = b;
      lowest_ = std::min(lowest_, b);
    }
    buckets_[b].set(cell, key, at.index);
  }

  /// Takes `cell` out of the queue; nothing when it is not queued.
  void remove(Cell cell)
  {
    QueuePlace& at = place_(cell);
    if (at.bucket == kNotQueued) {
      return;
    }
    buckets_[at.bucket].remove(cell, at.index);
    at.bucket = kNotQueued;
    --size_;
  }

  void pop() { remove(top().cell); }

  /// Empties the queue, marking every queued cell as not queued.
  void clear()
  {
    for (Bucket& bucket : buckets_) {
      for (const Entry& e : bucket.entries()) {
        place_(e.cell).bucket = kNotQueued;
      }
      bucket.clear();
    }
    size_ = 0;
    lowest_ = kNotQueued;
  }

private:
  /// The lowest bucket that holds anything; the queue must not be empty.
  std::uint32_t lowest()
  {
    while (buckets_[lowest_].empty()) {
      ++lowest_;
    }
    return lowest_;
  }

  PlaceOf place_;
  LevelOf level_;
  std::vector<Bucket> buckets_;
  std::vector<std::uint64_t> ages_;  // per bucket: the age its keys are up to date with
  std::uint64_t age_ = 0;
  std::uint32_t lowest_ = kNotQueued;  // no bucket below it holds anything
  std::size_t size_ = 0;
};

}  // namespace quad::planning
