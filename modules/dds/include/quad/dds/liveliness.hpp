// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Keeps a MANUAL_BY_TOPIC writer alive in wall time, whatever its samples' schedule.

#include <condition_variable>
#include <mutex>
#include <thread>

#include "quad/dds/endpoint.hpp"

namespace quad::dds {

/// Asserts a writer's liveliness four times per lease (its QoS profile's), from a thread of
/// its own, until destroyed: a process busy in a long computation, or one that writes on a
/// sim-time schedule while the sim clock waits, stays alive to its readers, and one killed
/// or stopped does not. Nothing for a writer without a lease.
class LivelinessKeeper {
public:
  explicit LivelinessKeeper(WriterEndpoint& writer);
  ~LivelinessKeeper();
  LivelinessKeeper(const LivelinessKeeper&) = delete;
  LivelinessKeeper& operator=(const LivelinessKeeper&) = delete;

  /// Stops asserting, at once (the destructor does); the writer may go after it.
  void stop();

private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool quit_ = false;
  std::thread thread_;
};

}  // namespace quad::dds
