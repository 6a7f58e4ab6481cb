// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/waker.hpp"

#include <chrono>

#include "quad/common/time.hpp"

namespace quad::dds {

void Waker::notify()
{
  if (runner_ && runner_()) {
    return;
  }
  {
    std::lock_guard lock(mutex_);
    pending_ = true;
  }
  cv_.notify_one();
}

bool Waker::waitUntil(std::int64_t deadline_steady_ns)
{
  std::unique_lock lock(mutex_);
  const auto timeout = std::chrono::nanoseconds(deadline_steady_ns - common::steadyTimeNs());
  const bool notified = cv_.wait_for(lock, timeout, [this] { return pending_; });
  pending_ = false;
  return notified;
}

}  // namespace quad::dds
