// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Wakes a node's loop when data or events arrive, or when it must stop.

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>

namespace quad::dds {

class Waker {
public:
  /// Safe from any thread (listener callbacks), never blocks for long. With a runner (below)
  /// that took the notification, nothing else happens.
  void notify();

  /// `run` is offered each notification first, on the notifying thread: true when it did the
  /// work the notification asks for there and then, false to have the waiting loop woken as
  /// without it. Set once, before anything notifies.
  void setRunner(std::function<bool()> run) { runner_ = std::move(run); }

  /// Waits until notified or until `deadline_steady_ns` (CLOCK_MONOTONIC). Returns true when
  /// notified. A notification that came before the call is not lost.
  bool waitUntil(std::int64_t deadline_steady_ns);

private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false;
  std::function<bool()> runner_;
};

}  // namespace quad::dds
