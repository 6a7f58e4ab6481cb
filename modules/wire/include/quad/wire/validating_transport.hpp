// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The validating transport: a Fast DDS transport layer (ChainingTransport) in front of UDP
/// that drops every received datagram checkRtpsDatagram (rtps_check.hpp) finds malformed,
/// before Fast DDS's parser sees it. On in every quad participant that uses UDP
/// (ParticipantOptions::validate_datagrams).

#include <cstdint>
#include <memory>
#include <string>

#include <fastdds/rtps/transport/TransportDescriptorInterface.h>

namespace quad::wire {

/// The descriptor to put in a participant's user transports in place of `inner` (UDPv4, or a
/// layer in front of it).
std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> validatingTransport(
    std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> inner);

/// Datagrams this process dropped as malformed since it started, and the last one's defect
/// with where it came from.
struct MalformedDatagrams {
  std::uint64_t count = 0;
  std::uint64_t checked = 0;  ///< every datagram the layer saw
  std::string last;           ///< "from 127.0.0.1:41234, 92 bytes: at byte 20: DATA_FRAG: ..."
};
MalformedDatagrams malformedDatagrams();
/// malformedDatagrams().count without a lock or a copy: cheap enough to poll in a loop.
std::uint64_t malformedDatagramCount();

}  // namespace quad::wire
