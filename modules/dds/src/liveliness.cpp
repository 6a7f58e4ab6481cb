// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/liveliness.hpp"

#include <chrono>

namespace quad::dds {

LivelinessKeeper::LivelinessKeeper(WriterEndpoint& writer)
{
  const auto lease_ns = writer.livelinessLeaseNs();
  if (!lease_ns) {
    return;
  }
  const std::chrono::nanoseconds period(*lease_ns / 4);
  thread_ = std::thread([this, &writer, period] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!cv_.wait_for(lock, period, [this] { return quit_; })) {
      writer.assertLiveliness();
    }
  });
}

LivelinessKeeper::~LivelinessKeeper() { stop(); }

void LivelinessKeeper::stop()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) {
    thread_.join();
  }
}

}  // namespace quad::dds
