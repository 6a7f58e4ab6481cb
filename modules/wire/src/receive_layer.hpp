// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The base of quad's transport layers in front of UDP (the fault layer, the validating
/// transport): a Fast DDS ChainingTransport that acts on received datagrams only and sends
/// through the transport below untouched.

#include <fastdds/rtps/transport/ChainingTransport.h>
#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>

namespace quad::wire {

class ReceiveLayer : public eprosima::fastdds::rtps::ChainingTransport {
public:
  explicit ReceiveLayer(const eprosima::fastdds::rtps::ChainingTransportDescriptor& d) : ChainingTransport(d) {}

  bool send(eprosima::fastrtps::rtps::SenderResource* low_sender_resource,
            const eprosima::fastrtps::rtps::octet* send_buffer, uint32_t send_buffer_size,
            eprosima::fastrtps::rtps::LocatorsIterator* destination_locators_begin,
            eprosima::fastrtps::rtps::LocatorsIterator* destination_locators_end,
            const std::chrono::steady_clock::time_point& timeout) override
  {
    return low_sender_resource->send(send_buffer, send_buffer_size, destination_locators_begin,
                                     destination_locators_end, timeout);
  }
};

}  // namespace quad::wire
