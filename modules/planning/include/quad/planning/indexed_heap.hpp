// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A priority queue of cells that holds each cell at most once and changes or removes a
/// queued cell's key in place: the queue D* Lite's pseudocode assumes (U.Update, U.Remove;
/// Koenig & Likhachev 2002) and the decrease-key of A*. Where a cell sits in the heap is kept
/// by the caller, in the cell's own search state, and reached through a function, so the
/// queue needs no hashing of its own. A queue with lazy deletion instead grows by every
/// change of key, and most of a long search's time goes into popping what is out of date.
///
/// A 4-ary heap: half the depth of a binary one, and its children are neighbours in memory.
/// It orders itself when first asked for its top: cells queued into an empty heap are only
/// appended until then, so a heap that is filled and then mostly left alone (a bucket of
/// BucketQueue above the lowest) costs nothing to fill.

#include <compare>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace quad::planning {

/// A cell's slot when the cell is not in the queue.
inline constexpr std::uint32_t kNotQueued = std::numeric_limits<std::uint32_t>::max();

/// Key needs operator<=> (a weak or partial order); Slot is callable as `std::uint32_t& slot(std::int64_t cell)`, the
/// caller's record of the cell's place, kNotQueued when the cell is not in the queue. Equal
/// keys come out by cell number, smallest first, so a search's order does not depend on the
/// queue's history.
template <typename Key, typename Slot>
class IndexedHeap {
public:
  using Cell = std::int64_t;
  struct Entry {
    Key key;
    Cell cell;
  };

  explicit IndexedHeap(Slot slot) : slot_(std::move(slot)) {}

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  /// The least entry; the heap must not be empty.
  const Entry& top()
  {
    order();
    return entries_.front();
  }
  /// Every queued entry, in no particular order.
  const std::vector<Entry>& entries() const { return entries_; }

  /// Queues `cell` with `key`, or changes its key when it is queued already.
  void set(Cell cell, const Key& key) { set(cell, key, slot_(cell)); }
  /// The same, with the cell's slot already found by the caller.
  void set(Cell cell, const Key& key, std::uint32_t& at)
  {
    if (at == kNotQueued) {
      at = static_cast<std::uint32_t>(entries_.size());
      entries_.push_back({key, cell});
      if (ordered_) {
        up(at);
      }
      return;
    }
    const std::uint32_t i = at;
    if (!ordered_) {
      entries_[i].key = key;
      return;
    }
    const bool lower = before({key, cell}, entries_[i]);
    entries_[i].key = key;
    if (lower) {
      up(i);
    } else {
      down(i);
    }
  }

  /// Takes `cell` out of the queue; nothing when it is not queued.
  void remove(Cell cell) { remove(cell, slot_(cell)); }
  /// The same, with the cell's slot already found by the caller.
  void remove(Cell cell, std::uint32_t& at)
  {
    if (at == kNotQueued) {
      return;
    }
    const std::uint32_t i = at;
    at = kNotQueued;
    const Entry last = entries_.back();
    entries_.pop_back();
    if (entries_.empty()) {
      ordered_ = false;
    }
    if (last.cell == cell) {
      return;
    }
    // The last entry fills the hole; it may belong above or below it.
    place(i, last);
    if (ordered_) {
      up(i);
      down(slot_(last.cell));
    }
  }

  void pop() { remove(top().cell); }

  /// Empties the queue, marking every queued cell as not queued, and gives what it held.
  std::vector<Entry> take()
  {
    for (const Entry& e : entries_) {
      slot_(e.cell) = kNotQueued;
    }
    ordered_ = false;
    return std::exchange(entries_, {});
  }

  /// Empties the queue, marking every queued cell as not queued.
  void clear()
  {
    for (const Entry& e : entries_) {
      slot_(e.cell) = kNotQueued;
    }
    entries_.clear();
    ordered_ = false;
  }

private:
  static constexpr std::uint32_t kArity = 4;

  static bool before(const Entry& a, const Entry& b)
  {
    const auto order = a.key <=> b.key;  // one comparison of the keys, not two
    return order != 0 ? order < 0 : a.cell < b.cell;
  }

  /// Makes a heap of what was appended (Floyd: sift down every parent, last first).
  void order()
  {
    if (ordered_) {
      return;
    }
    ordered_ = true;
    const auto n = static_cast<std::uint32_t>(entries_.size());
    for (std::uint32_t i = n > 1 ? (n - 2) / kArity + 1 : 0; i-- > 0;) {
      down(i);
    }
  }

  void place(std::uint32_t i, const Entry& e)
  {
    entries_[i] = e;
    slot_(e.cell) = i;
  }

  void up(std::uint32_t i)
  {
    const Entry e = entries_[i];
    while (i > 0) {
      const std::uint32_t parent = (i - 1) / kArity;
      if (!before(e, entries_[parent])) {
        break;
      }
      place(i, entries_[parent]);
      i = parent;
    }
    place(i, e);
  }

  void down(std::uint32_t i)
  {
    const Entry e = entries_[i];
    const auto n = static_cast<std::uint32_t>(entries_.size());
    for (;;) {
      const std::uint32_t first = kArity * i + 1;
      if (first >= n) {
        break;
      }
      std::uint32_t best = first;
      const std::uint32_t end = first + kArity < n ? first + kArity : n;
      for (std::uint32_t c = first + 1; c < end; ++c) {
        if (before(entries_[c], entries_[best])) {
          best = c;
        }
      }
      if (!before(entries_[best], e)) {
        break;
      }
      place(i, entries_[best]);
      i = best;
    }
    place(i, e);
  }

  Slot slot_;
  std::vector<Entry> entries_;
  bool ordered_ = false;  // a heap; when not, entries_ is in the order of arrival
};

}  // namespace quad::planning
