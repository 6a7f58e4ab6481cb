// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Wakes a node's loop when data or events arrive, or when it must stop.

#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace quad::dds {

class Waker {
public:
  /// Safe from any thread (listener callbacks), never blocks for long.
  void notify();

  /// Waits until notified or until `deadline_steady_ns` (CLOCK_MONOTONIC). Returns true when
  /// notified. A notification that came before the call is not lost.
  bool waitUntil(std::int64_t deadline_steady_ns);

private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false;
};

}  // namespace quad::dds
