// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Whether another module is alive, from its heartbeat writer's liveliness: MANUAL_BY_TOPIC
/// with a 0.5 s lease, asserted by each node from a thread of its own (docs/topics.md). A busy
/// module keeps it; a stopped, killed or cut-off one loses it within the lease. Data writers'
/// AUTOMATIC liveliness says less: Fast DDS 2.9 keeps a dead writer alive while another of
/// its participant's kind lives.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"

namespace quad::dds {

class ModuleWatch {
public:
  enum class State {
    kUnknown,  ///< no heartbeat of the module yet
    kAlive,    ///< a heartbeat writer of the module is alive
    kLost,     ///< every heartbeat writer of the module lost its liveliness or went away
  };

  /// `module_name` as in Heartbeat.module_name ("mapping", ...).
  ModuleWatch(Participant& participant, std::string module_name, Waker* waker);

  /// Takes the heartbeats and liveliness changes that arrived; the module's state after them.
  State update();

  const std::string& moduleName() const { return module_; }
  /// The heartbeat's liveliness lease [ns] (the QoS profile's, 0.5 s); none when infinite.
  std::optional<std::int64_t> leaseNs() const { return heartbeats_.livelinessLeaseNs(); }

private:
  Subscriber<msg::Heartbeat> heartbeats_;
  std::string module_;
  std::map<std::uint64_t, bool> writers_;  // the module's heartbeat writers: alive or not
};

}  // namespace quad::dds
