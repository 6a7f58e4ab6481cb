#include "quad/dds/message_types.hpp"

namespace quad::dds {

void vehicleKeyHash(std::uint32_t vehicle_id, eprosima::fastrtps::rtps::InstanceHandle_t& handle)
{
  for (int i = 4; i < 16; ++i) {
    handle.value[i] = 0;
  }
  handle.value[0] = static_cast<eprosima::fastrtps::rtps::octet>(vehicle_id >> 24);
  handle.value[1] = static_cast<eprosima::fastrtps::rtps::octet>(vehicle_id >> 16);
  handle.value[2] = static_cast<eprosima::fastrtps::rtps::octet>(vehicle_id >> 8);
  handle.value[3] = static_cast<eprosima::fastrtps::rtps::octet>(vehicle_id);
}

}  // namespace quad::dds
