// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A typed writer on a topic contract.

#include <cstdint>
#include <optional>

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
  Publisher(Participant& participant, const Topic<Message>& topic,
            std::optional<eprosima::fastdds::dds::DataWriterQos> qos = std::nullopt)
      : WriterEndpoint(participant, topic.info,
                       eprosima::fastdds::dds::TypeSupport(
                           new typename MessageTraits<Message>::PubSubType()),
                       std::move(qos)),
        vehicle_id_(participant.options().vehicle_id)
  {
  }

  /// Returns false (counted, reported as an event) when the middleware refused the sample.
  bool write(Message& sample)
  {
    if constexpr (MessageTraits<Message>::kHasHeader) {
      auto& header = sample.header();
      header.vehicle_id(vehicle_id_);
      header.seq(seq_ + 1);  // a number is used only by a sample the middleware took
      header.publish_ns(common::wallTimeNs());
    }
    const bool written = writeSample(&sample);
    if (written) {
      ++seq_;
    }
    return written;
  }

  /// For a sample built in place: `publisher.write(toMessage(x))`.
  bool write(Message&& sample)
  {
    Message& filled = sample;
    return write(filled);
  }

  /// The Header.seq of the newest sample the middleware took (0: none yet).
  std::uint64_t lastSeq() const { return seq_; }

private:
  std::uint32_t vehicle_id_;
  std::uint64_t seq_ = 0;
};

}  // namespace quad::dds
