// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Polling a condition with a deadline, for tests that wait on other threads or processes.

#include <chrono>
#include <functional>
#include <thread>

namespace quad::test {

/// Polls `condition` every 5 ms until it holds (true) or `timeout` passes (false).
inline bool waitFor(const std::function<bool()>& condition,
                    std::chrono::milliseconds timeout = std::chrono::seconds(10))
{
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace quad::test
