// SPDX-License-Identifier: BSD-3-Clause
// Fuzz target: every IDL type's deserialisation, as a typed reader runs it (the IDL bounds
// check, then the generated Fast CDR code), and the schema-driven decoder `quad topic echo`
// uses. The first byte picks the type; the rest is the serialized payload.
#include <fastdds/rtps/common/SerializedPayload.h>

#include "harness.hpp"
#include "quad/dds/message_types.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/introspection/idl.hpp"

namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

template <class Message>
void deserialize(const std::uint8_t* data, std::size_t size)
{
  using Traits = quad::dds::MessageTraits<Message>;
  typename Traits::PubSubType type;
  SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  std::copy(data, data + size, payload.data);
  payload.length = static_cast<std::uint32_t>(size);
  Message message;
  (void)type.deserialize(&payload, &message);
  try {
    (void)quad::introspection::decodeCdr(quad::introspection::quadSchema(), Traits::kTypeName,
                                         std::span<const std::uint8_t>(data, size));
  } catch (const std::exception&) {
    // refused, as it should be: malformed input is an error, never a crash
  }
}

template <class Message>
std::string serializedDefault(std::uint8_t index)
{
  typename quad::dds::MessageTraits<Message>::PubSubType type;
  Message message;
  SerializedPayload_t payload(type.m_typeSize);
  type.serialize(&message, &payload);
  return std::string(1, static_cast<char>(index)) +
         std::string(reinterpret_cast<const char*>(payload.data), payload.length);
}

template <class... Messages>
struct Types {
  static constexpr std::size_t kCount = sizeof...(Messages);

  static void run(std::size_t index, const std::uint8_t* data, std::size_t size)
  {
    std::size_t i = 0;
    ((i++ == index ? deserialize<Messages>(data, size) : void()), ...);
  }

  static std::vector<std::string> defaults()
  {
    std::vector<std::string> out;
    std::uint8_t i = 0;
    (out.push_back(serializedDefault<Messages>(i++)), ...);
    return out;
  }
};

using quad::msg::ActuatorCommand, quad::msg::BaroAltitude, quad::msg::ControlReference, quad::msg::ControlStatus, quad::msg::EstimatedState, quad::msg::FaultCommand,
    quad::msg::Goal, quad::msg::Heartbeat, quad::msg::Imu, quad::msg::LockstepReport, quad::msg::MagneticField, quad::msg::MapSnapshot,
    quad::msg::MapStats, quad::msg::MapUpdate, quad::msg::Path, quad::msg::PointCloud, quad::msg::PositionFix, quad::msg::SimClock,
    quad::msg::SimEvent, quad::msg::Trajectory, quad::msg::VehicleCommand, quad::msg::VehicleState;
using All = Types<ActuatorCommand, BaroAltitude, ControlReference, ControlStatus, EstimatedState, FaultCommand, Goal, Heartbeat, Imu,
                  LockstepReport, MagneticField, MapSnapshot, MapStats, MapUpdate, Path, PointCloud, PositionFix, SimClock,
                  SimEvent, Trajectory, VehicleCommand, VehicleState>;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0) {
    return 0;
  }
  All::run(data[0] % All::kCount, data + 1, size - 1);
  return 0;
}

std::vector<std::string> quad::fuzz::seeds() { return All::defaults(); }
