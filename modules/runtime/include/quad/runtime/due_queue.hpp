// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Inputs held until they are due (DESIGN.md §5). In lockstep an input takes effect at a sim
/// time fixed by its stamp, not when it happens to arrive, so that runs repeat: a path with the
/// first state after its stamp, an operator's goal the contract's delay after its stamp, an IMU
/// sample with the first state stamped after it. A node holds each input it takes with the sim
/// time it is due at, and releases what is due as it handles each time. Or with another
/// measure that only grows as the node handles its times: the planner holds a map update
/// until the clock's count of depth frames due reaches the frames the update accounts for.
/// No DDS.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>

namespace quad::runtime {

/// [ns] The due time of an input stamped `stamp_ns` that is answered by the first time handled
/// after it: a state stamped t is answered with what was stamped before t only.
constexpr std::int64_t dueAfter(std::int64_t stamp_ns) { return stamp_ns + 1; }

/// Items held with their due times and released in the order held: an item waits behind one
/// held before it, even one due later (the samples of one topic are due in the order they were
/// sent, and a reader takes them in that order), so the queue never reorders a topic.
template <typename T>
class DueQueue {
public:
  /// Holds `item` until the time handled reaches `due_ns`.
  void hold(std::int64_t due_ns, T item) { items_.emplace_back(due_ns, std::move(item)); }

  /// Hands `apply` every item due at or before `now_ns`, oldest first, each once, until the
  /// first one that is not; returns how many it handed.
  template <typename Apply>
  std::size_t release(std::int64_t now_ns, Apply&& apply)
  {
    std::size_t released = 0;
    while (!items_.empty() && items_.front().first <= now_ns) {
      T item = std::move(items_.front().second);
      items_.pop_front();
      apply(item);
      ++released;
    }
    return released;
  }

  /// The oldest item if it is due at or before `now_ns`, for inputs applied one a time handled
  /// (an operator's commands, each answered by the tick that applies it); none otherwise.
  std::optional<T> releaseOne(std::int64_t now_ns)
  {
    if (items_.empty() || items_.front().first > now_ns) {
      return std::nullopt;
    }
    std::optional<T> item(std::move(items_.front().second));
    items_.pop_front();
    return item;
  }

  /// Holds `item` due at `due_ns`, for a topic whose due times never fall as sent (the
  /// mapper's counts of depth frames, its snapshots' stamps): an item held last that is due
  /// later than this one was damaged on the way, and held it would hold this one, and every
  /// later one, back until its own time. Each such is handed to `dropped` and let go first.
  template <typename Dropped>
  void holdRising(std::int64_t due_ns, T item, Dropped&& dropped)
  {
    while (!items_.empty() && items_.back().first > due_ns) {
      dropped(std::as_const(items_.back().second));
      items_.pop_back();
    }
    hold(due_ns, std::move(item));
  }

  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  /// [ns] When the oldest item is due; none when nothing is held.
  std::optional<std::int64_t> nextDueNs() const
  {
    if (items_.empty()) {
      return std::nullopt;
    }
    return items_.front().first;
  }

private:
  std::deque<std::pair<std::int64_t, T>> items_;
};

}  // namespace quad::runtime
