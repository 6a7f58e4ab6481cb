// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A Fast DDS transport layer (ChainingTransport) in front of UDPv4 that applies a
/// participant's DatagramFaults to every datagram it receives.

#include <memory>

#include <fastdds/rtps/transport/TransportDescriptorInterface.h>

#include "quad/wire/datagram_faults.hpp"

namespace quad::wire {

/// The descriptor to put in a participant's user transports (builtin transports off, so that
/// no datagram goes around the layer).
std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> faultyUdpTransport(
    std::shared_ptr<DatagramFaults> faults, std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface> udp);

}  // namespace quad::wire
