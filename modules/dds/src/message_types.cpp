// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/message_types.hpp"

#include <atomic>
#include <map>
#include <mutex>
#include <span>

#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"

namespace quad::dds {

namespace {
std::mutex rejected_mutex;
RejectedPayloads rejected;
std::atomic<std::uint64_t> rejected_count{0};
std::map<std::string, std::uint64_t, std::less<>> rejected_by_type;
}  // namespace

bool payloadKeepsToIdl(std::string_view type_name, const eprosima::fastrtps::rtps::SerializedPayload_t& payload)
{
  const std::span<const std::uint8_t> bytes(payload.data, payload.length);
  const auto* checker = introspection::quadBoundsChecker(type_name);
  const std::string why = checker != nullptr ? checker->check(bytes)
                                             : introspection::checkBounds(introspection::quadSchema(), type_name, bytes);
  if (why.empty()) {
    return true;
  }
  countRejectedPayload(type_name, why);
  return false;
}

void countRejectedPayload(std::string_view type_name, const std::string& why)
{
  std::lock_guard lock(rejected_mutex);
  ++rejected.count;
  ++rejected_by_type[std::string(type_name)];
  rejected.last = std::string(type_name) + ": " + why;
  rejected_count.store(rejected.count, std::memory_order_relaxed);
}

RejectedPayloads rejectedPayloads()
{
  std::lock_guard lock(rejected_mutex);
  return rejected;
}

std::uint64_t rejectedPayloadCount()
{
  return rejected_count.load(std::memory_order_relaxed);
}

std::uint64_t rejectedPayloadCount(std::string_view type_name)
{
  if (rejected_count.load(std::memory_order_relaxed) == 0) {
    return 0;
  }
  std::lock_guard lock(rejected_mutex);
  const auto it = rejected_by_type.find(type_name);
  return it == rejected_by_type.end() ? 0 : it->second;
}

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
