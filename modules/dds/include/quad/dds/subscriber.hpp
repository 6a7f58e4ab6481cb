// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A typed reader on a topic contract.

#include <optional>
#include <span>
#include <vector>

#include "quad/dds/endpoint.hpp"

namespace quad::dds {

/// Takes samples of one topic. Arrivals notify the given Waker (the node's loop); statuses
/// go to the participant's event queue.
template <class Message>
class Subscriber : public ReaderEndpoint {
public:
  /// `partition`: whose partitions it reads in (vehiclePartitions); kEveryVehicle for a
  /// reader of every vehicle's samples in a participant of one vehicle.
  Subscriber(Participant& participant, const Topic<Message>& topic, Waker* waker = nullptr,
             std::optional<eprosima::fastdds::dds::DataReaderQos> qos = std::nullopt,
             std::optional<std::uint32_t> partition = std::nullopt)
      : ReaderEndpoint(participant, topic.info,
                       eprosima::fastdds::dds::TypeSupport(
                           new typename MessageTraits<Message>::PubSubType()),
                       waker, std::move(qos), partition)
  {
  }

  /// The next unread sample of this participant's vehicle, if any; `writer`, when given,
  /// receives its writer's id (the one takeLivelinessChanges names). Samples of another
  /// vehicle (Header.vehicle_id) are dropped and counted (foreignSamples()); a display
  /// schema, without a Header, is taken whole.
  std::optional<Message> take(std::uint64_t* writer = nullptr)
  {
    Message sample;
    while (takeSample(&sample, writer)) {
      if constexpr (!MessageTraits<Message>::kHasHeader) {
        return sample;
      } else if (ownVehicle(sample.header().vehicle_id())) {
        return sample;
      }
    }
    return std::nullopt;
  }

  /// The next unread sample of any of the `served` vehicles (a plant simulating a fleet takes
  /// every vehicle's commands); samples of other vehicles are dropped and counted as take()
  /// drops them.
  std::optional<Message> takeServed(std::span<const std::uint32_t> served)
  {
    static_assert(MessageTraits<Message>::kHasHeader, "only a sample with a Header names its vehicle");
    Message sample;
    while (takeSample(&sample)) {
      if (servedVehicle(sample.header().vehicle_id(), served)) {
        return sample;
      }
    }
    return std::nullopt;
  }

  /// The next unread sample of whichever vehicle (a planner hearing the other vehicles'
  /// paths, the launcher every module's heartbeat): nothing is dropped. `writer` as take's.
  std::optional<Message> takeAnyVehicle(std::uint64_t* writer = nullptr)
  {
    Message sample;
    return takeSample(&sample, writer) ? std::optional<Message>(std::move(sample)) : std::nullopt;
  }

  /// Every unread sample of this participant's vehicle, oldest first.
  std::vector<Message> takeAll()
  {
    std::vector<Message> out;
    while (auto sample = take()) {
      out.push_back(std::move(*sample));
    }
    return out;
  }

  /// Every unread sample of any of the `served` vehicles, oldest first (takeServed).
  std::vector<Message> takeAll(std::span<const std::uint32_t> served)
  {
    std::vector<Message> out;
    while (auto sample = takeServed(served)) {
      out.push_back(std::move(*sample));
    }
    return out;
  }
};

}  // namespace quad::dds
