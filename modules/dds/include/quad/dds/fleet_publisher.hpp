// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A writer per vehicle of a fleet, each in its vehicle's partition (vehiclePartitions): a
/// plant simulating several vehicles sends each vehicle's samples to that vehicle's modules
/// (and to the tools, which read every partition), not to every vehicle's.

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

#include "quad/dds/publisher.hpp"

namespace quad::dds {

template <class Message>
class FleetPublisher {
public:
  FleetPublisher(Participant& participant, const Topic<Message>& topic, std::span<const std::uint32_t> vehicles)
      : topic_name_(topic.info.name)
  {
    for (const std::uint32_t id : vehicles) {
      writers_.try_emplace(id, std::make_unique<Publisher<Message>>(participant, topic, std::nullopt, id));
    }
  }

  /// Writes a sample about `vehicle_id`, one of the fleet's (Publisher::writeFor).
  bool writeFor(std::uint32_t vehicle_id, Message& sample) { return of(vehicle_id).writeFor(vehicle_id, sample); }
  bool writeFor(std::uint32_t vehicle_id, Message&& sample)
  {
    Message& filled = sample;
    return writeFor(vehicle_id, filled);
  }

  /// The Header.seq of the newest sample written about `vehicle_id` (0: none yet).
  std::uint64_t lastSeq(std::uint32_t vehicle_id) const
  {
    const auto it = writers_.find(vehicle_id);
    return it == writers_.end() ? 0 : it->second->lastSeq(vehicle_id);
  }

  /// Waits until every vehicle's matched reliable readers acknowledged what was written;
  /// false on timeout (the wait is `timeout` per vehicle at most).
  bool waitForAcknowledgments(std::chrono::milliseconds timeout)
  {
    bool all = true;
    for (auto& [id, writer] : writers_) {
      all = writer->waitForAcknowledgments(timeout) && all;
    }
    return all;
  }

private:
  Publisher<Message>& of(std::uint32_t vehicle_id)
  {
    const auto it = writers_.find(vehicle_id);
    if (it == writers_.end()) {
      throw std::logic_error(std::string(topic_name_) + ": vehicle " + std::to_string(vehicle_id) +
                             " is not one of the fleet's");
    }
    return *it->second;
  }

  std::string_view topic_name_;
  std::map<std::uint32_t, std::unique_ptr<Publisher<Message>>> writers_;
};

}  // namespace quad::dds
