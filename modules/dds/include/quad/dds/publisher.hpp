// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A typed writer on a topic contract.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "quad/common/time.hpp"
#include "quad/dds/endpoint.hpp"

namespace quad::dds {

/// Writes samples of one topic. It owns its DataWriter (RAII) and fills each sample's
/// Header: per-writer sequence number, publish time and vehicle id. The caller sets
/// header().stamp_ns(), the time the sample is about. (A display schema has no Header: its
/// sample is written as it is.)
template <class Message>
class Publisher : public WriterEndpoint {
public:
  /// `partition`: the vehicle whose partitions it writes in (vehiclePartitions); by default
  /// the participant's.
  Publisher(Participant& participant, const Topic<Message>& topic,
            std::optional<eprosima::fastdds::dds::DataWriterQos> qos = std::nullopt,
            std::optional<std::uint32_t> partition = std::nullopt)
      : WriterEndpoint(participant, topic.info,
                       eprosima::fastdds::dds::TypeSupport(
                           new typename MessageTraits<Message>::PubSubType()),
                       std::move(qos), partition),
        vehicle_id_(participant.options().vehicle_id)
  {
  }

  /// Returns false (counted, reported as an event) when the middleware refused the sample.
  bool write(Message& sample) { return writeFor(vehicle_id_, sample); }

  /// For a sample built in place: `publisher.write(toMessage(x))`.
  bool write(Message&& sample)
  {
    Message& filled = sample;
    return write(filled);
  }

  /// Writes a sample about another vehicle than the participant's (a plant simulating a
  /// fleet): its Header names that vehicle, and each vehicle's samples are numbered on their
  /// own, so that its readers see no gap.
  bool writeFor(std::uint32_t vehicle_id, Message& sample)
  {
    std::uint64_t& seq = seqOf(vehicle_id);
    if constexpr (MessageTraits<Message>::kHasHeader) {
      auto& header = sample.header();
      header.vehicle_id(vehicle_id);
      header.seq(seq + 1);  // a number is used only by a sample the middleware took
      header.publish_ns(common::wallTimeNs());
    }
    const bool written = writeSample(&sample);
    if (written) {
      ++seq;
    }
    return written;
  }
  bool writeFor(std::uint32_t vehicle_id, Message&& sample)
  {
    Message& filled = sample;
    return writeFor(vehicle_id, filled);
  }

  /// The Header.seq of the newest sample the middleware took (0: none yet), of the
  /// participant's vehicle or of `vehicle_id`.
  std::uint64_t lastSeq() const { return lastSeq(vehicle_id_); }
  std::uint64_t lastSeq(std::uint32_t vehicle_id) const
  {
    for (const auto& [id, seq] : seqs_) {
      if (id == vehicle_id) {
        return seq;
      }
    }
    return 0;
  }

private:
  std::uint64_t& seqOf(std::uint32_t vehicle_id)
  {
    for (auto& [id, seq] : seqs_) {
      if (id == vehicle_id) {
        return seq;
      }
    }
    return seqs_.emplace_back(vehicle_id, 0).second;
  }

  std::uint32_t vehicle_id_;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> seqs_;  // per vehicle written for: its last seq
};

}  // namespace quad::dds
