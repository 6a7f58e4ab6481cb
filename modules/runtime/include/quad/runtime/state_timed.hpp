// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Inputs handled with the vehicle state of their own time (DESIGN.md §5): a depth cloud is
/// placed on the body's pose at its stamp, which a state stamped at or after it gives. In
/// lockstep such an input waits for that state, not one carried on to it, so that runs repeat;
/// it goes without one only when none will come: a state of its time or later came (it fell in
/// a gap), or the clock of its time said no state was sent. In real time it goes once the pose
/// of its time is known, or after waiting a limit of sim time for it. Held in the order they
/// came, so one topic is never reordered. No DDS.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <utility>

namespace quad::runtime {

/// What the reader knows of the states and the clock as it releases what it holds.
struct StateProgress {
  bool lockstep = false;
  std::int64_t states_heard_ns = -1;  ///< [ns] the newest state's stamp, -1 before the first
  std::int64_t clock_ns = 0;          ///< [ns] the newest clock time
};

template <typename T>
class StateTimed {
public:
  /// `real_time_wait_ns`: sim time an input waits for the pose of its time in real time.
  explicit StateTimed(std::int64_t real_time_wait_ns) : real_time_wait_ns_(real_time_wait_ns) {}

  void hold(std::int64_t stamp_ns, T item) { items_.emplace_back(stamp_ns, std::move(item)); }

  /// Hands `apply(item)` every input held whose state came or will not come, oldest first,
  /// until the first that must still wait; returns how many it handed. `pose_known(stamp)`:
  /// the reader can place something stamped then (real time); `state_sent_at(stamp)`: false
  /// only when a clock sample of that time said no state of that time was sent (lockstep).
  template <typename PoseKnown, typename StateSentAt, typename Apply>
  std::size_t release(const StateProgress& progress, PoseKnown&& pose_known, StateSentAt&& state_sent_at,
                      Apply&& apply)
  {
    std::size_t released = 0;
    while (!items_.empty()) {
      const std::int64_t stamp = items_.front().first;
      const bool due = progress.states_heard_ns >= stamp ||
                       (progress.lockstep ? progress.clock_ns >= stamp && !state_sent_at(stamp)
                                          : pose_known(stamp) || progress.clock_ns - stamp > real_time_wait_ns_);
      if (!due) {
        break;
      }
      T item = std::move(items_.front().second);
      items_.pop_front();
      apply(item);
      ++released;
    }
    return released;
  }

  /// Drops every input held but the newest (a real-time reader that fell behind: the newest
  /// carries the freshest view); returns how many it dropped.
  std::size_t keepNewest()
  {
    if (items_.size() <= 1) {
      return 0;
    }
    const std::size_t dropped = items_.size() - 1;
    items_.erase(items_.begin(), items_.end() - 1);
    return dropped;
  }

  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  /// [ns] The oldest input's stamp; call only when something is held.
  std::int64_t oldestStampNs() const { return items_.front().first; }
  /// The input held last; call only when something is held.
  const T& newest() const { return items_.back().second; }

private:
  std::int64_t real_time_wait_ns_;
  std::deque<std::pair<std::int64_t, T>> items_;
};

}  // namespace quad::runtime
