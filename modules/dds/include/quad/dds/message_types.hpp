// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Compile-time facts about each generated message type: its TopicDataType, its IDL file,
/// and whether it leads with quad's Header (quad's messages do; Foxglove's display schemas,
/// foxglove::*, do not).
///
/// fastddsgen 2.3 serialises a nested `@key Header header` member whole as the key, so every
/// sample (new stamp, new seq) would become a new DDS instance. VehicleKeyedType computes the
/// key hash as the IDL says it should be: from header.vehicle_id alone (the big-endian CDR of
/// the key members, zero-padded to 16 bytes, per DDS-XTypes 7.6.8).

#include <cstdint>
#include <string>
#include <string_view>

#include <fastcdr/exceptions/Exception.h>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <quad/msg/ActuatorCommandPubSubTypes.h>
#include <quad/msg/BaroAltitudePubSubTypes.h>
#include <quad/msg/BatteryStatePubSubTypes.h>
#include <quad/msg/CommandAckPubSubTypes.h>
#include <quad/msg/ControlReferencePubSubTypes.h>
#include <quad/msg/ControlStatusPubSubTypes.h>
#include <quad/msg/EstimatedStatePubSubTypes.h>
#include <quad/msg/FaultCommandPubSubTypes.h>
#include <quad/msg/GoalAckPubSubTypes.h>
#include <quad/msg/GoalPubSubTypes.h>
#include <quad/msg/HeartbeatPubSubTypes.h>
#include <quad/msg/ImuPubSubTypes.h>
#include <quad/msg/LockstepReportPubSubTypes.h>
#include <quad/msg/MagneticFieldPubSubTypes.h>
#include <quad/msg/MapSnapshotPubSubTypes.h>
#include <quad/msg/MapStatsPubSubTypes.h>
#include <quad/msg/MapUpdatePubSubTypes.h>
#include <quad/msg/PathPubSubTypes.h>
#include <quad/msg/PointCloudPubSubTypes.h>
#include <quad/msg/PositionFixPubSubTypes.h>
#include <quad/msg/RangePubSubTypes.h>
#include <quad/msg/SimClockPubSubTypes.h>
#include <quad/msg/SimEventPubSubTypes.h>
#include <quad/msg/TrajectoryPubSubTypes.h>
#include <quad/msg/VehicleCommandPubSubTypes.h>
#include <quad/msg/VehicleStatePubSubTypes.h>

#include <foxglove/FrameTransformsPubSubTypes.h>
#include <foxglove/LogPubSubTypes.h>
#include <foxglove/PointCloudPubSubTypes.h>
#include <foxglove/PosesInFramePubSubTypes.h>
#include <foxglove/SceneUpdatePubSubTypes.h>

#include "quad/common/payload_header.hpp"

namespace quad::dds {

/// Writes the key hash of a vehicle id into a DDS instance handle.
void vehicleKeyHash(std::uint32_t vehicle_id, eprosima::fastrtps::rtps::InstanceHandle_t& handle);

/// Whether a received payload of `type_name` keeps to its IDL (introspection::checkBounds):
/// the generated code reads a sequence of any length into a bounded one. A payload that
/// does not is counted and its fault kept for rejectedPayloads().
bool payloadKeepsToIdl(std::string_view type_name, const eprosima::fastrtps::rtps::SerializedPayload_t& payload);

/// Payloads this process refused since it started, and what was wrong with the last one.
struct RejectedPayloads {
  std::uint64_t count = 0;
  std::string last;  ///< "quad::msg::Path: waypoints_W: sequence length 5000 exceeds its bound 4096 at byte 52"
};
RejectedPayloads rejectedPayloads();
/// rejectedPayloads().count without a lock or a copy: cheap enough to poll in a loop.
std::uint64_t rejectedPayloadCount();
/// Payloads of one type this process refused: a reader of a reliable topic learns from it
/// that a sample the middleware counts as delivered never reached it.
std::uint64_t rejectedPayloadCount(std::string_view type_name);

/// Counts a payload refused for another reason than its IDL (payloadKeepsToIdl counts those).
void countRejectedPayload(std::string_view type_name, const std::string& why);

/// The generated TopicDataType, refusing payloads that break their IDL's bounds.
template <class Generated>
class CheckedType : public Generated {
public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override
  {
    if (!payloadKeepsToIdl(this->getName(), *payload)) {
      return false;
    }
    try {
      return Generated::deserialize(payload, data);
    } catch (const eprosima::fastcdr::exception::Exception& e) {
      // The generated code lets Fast CDR's refusals (a boolean byte of 2, say) escape, and a
      // reader thread that throws ends the process. The IDL check above catches those known.
      countRejectedPayload(this->getName(), e.what());
      return false;
    }
  }
};

/// A checked type whose key is computed from header.vehicle_id, which must be a vehicle id
/// (common::kMaxVehicleId).
///
/// A reader's history files each sample under the instance its key names, computed on
/// arrival by deserializing into one object it keeps for that and asking getKey, whether the
/// deserialization succeeded or not. So a bit flipped high in a vehicle id, or a refused
/// payload right after one, would invent an instance nobody wrote, and Fast DDS 2.9's
/// reader history can then fail its own assertion (`NEW_VIEW_STATE == view_state` in
/// DataReaderInstance) and end the process (seen: the planner's lockstep reader under the
/// link_corruption fault, a report for vehicle 2,147,483,648). A refused payload leaves
/// vehicle 0 behind, a key that exists, rather than the last one computed.
template <class Generated, class Message>
class VehicleKeyedType : public CheckedType<Generated> {
public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override
  {
    auto& header = static_cast<Message*>(data)->header();
    if (!CheckedType<Generated>::deserialize(payload, data)) {
      header.vehicle_id(0);
      return false;
    }
    if (header.vehicle_id() > common::kMaxVehicleId) {
      countRejectedPayload(this->getName(), "header.vehicle_id " + std::to_string(header.vehicle_id()) +
                                                " is not a vehicle id (at most " +
                                                std::to_string(common::kMaxVehicleId) + ")");
      header.vehicle_id(0);
      return false;
    }
    return true;
  }

  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool /*force_md5*/) override
  {
    vehicleKeyHash(static_cast<const Message*>(data)->header().vehicle_id(), *handle);
    return true;
  }
};

/// Specialised once per topic type by QUAD_DDS_MESSAGE below.
template <class Message>
struct MessageTraits;

#define QUAD_DDS_MESSAGE(Name)                                                            \
  template <>                                                                             \
  struct MessageTraits<quad::msg::Name> {                                                 \
    using PubSubType = VehicleKeyedType<quad::msg::Name##PubSubType, quad::msg::Name>;    \
    static constexpr bool kHasHeader = true;                                              \
    static constexpr std::string_view kTypeName = "quad::msg::" #Name;                   \
    static constexpr std::string_view kIdlFile = "quad/msg/" #Name ".idl";               \
    static std::uint32_t maxSerializedSize()                                              \
    {                                                                                     \
      return static_cast<std::uint32_t>(quad::msg::Name::getMaxCdrSerializedSize()) + 4;  \
    }                                                                                     \
  }

QUAD_DDS_MESSAGE(ActuatorCommand);
QUAD_DDS_MESSAGE(BaroAltitude);
QUAD_DDS_MESSAGE(BatteryState);
QUAD_DDS_MESSAGE(CommandAck);
QUAD_DDS_MESSAGE(ControlReference);
QUAD_DDS_MESSAGE(ControlStatus);
QUAD_DDS_MESSAGE(EstimatedState);
QUAD_DDS_MESSAGE(FaultCommand);
QUAD_DDS_MESSAGE(Goal);
QUAD_DDS_MESSAGE(GoalAck);
QUAD_DDS_MESSAGE(Heartbeat);
QUAD_DDS_MESSAGE(Imu);
QUAD_DDS_MESSAGE(LockstepReport);
QUAD_DDS_MESSAGE(MagneticField);
QUAD_DDS_MESSAGE(MapSnapshot);
QUAD_DDS_MESSAGE(MapStats);
QUAD_DDS_MESSAGE(MapUpdate);
QUAD_DDS_MESSAGE(Path);
QUAD_DDS_MESSAGE(PositionFix);
QUAD_DDS_MESSAGE(PointCloud);
QUAD_DDS_MESSAGE(Range);
QUAD_DDS_MESSAGE(SimClock);
QUAD_DDS_MESSAGE(SimEvent);
QUAD_DDS_MESSAGE(Trajectory);
QUAD_DDS_MESSAGE(VehicleCommand);
QUAD_DDS_MESSAGE(VehicleState);

#undef QUAD_DDS_MESSAGE

/// Foxglove's display schemas: no Header, no key (a display topic carries one vehicle's).
#define QUAD_DDS_DISPLAY_MESSAGE(Name)                                                    \
  template <>                                                                             \
  struct MessageTraits<foxglove::Name> {                                                  \
    using PubSubType = CheckedType<foxglove::Name##PubSubType>;                           \
    static constexpr bool kHasHeader = false;                                             \
    static constexpr std::string_view kTypeName = "foxglove::" #Name;                    \
    static constexpr std::string_view kIdlFile = "foxglove/" #Name ".idl";               \
    static std::uint32_t maxSerializedSize()                                              \
    {                                                                                     \
      return static_cast<std::uint32_t>(foxglove::Name::getMaxCdrSerializedSize()) + 4;   \
    }                                                                                     \
  }

QUAD_DDS_DISPLAY_MESSAGE(FrameTransforms);
QUAD_DDS_DISPLAY_MESSAGE(Log);
QUAD_DDS_DISPLAY_MESSAGE(PointCloud);
QUAD_DDS_DISPLAY_MESSAGE(PosesInFrame);
QUAD_DDS_DISPLAY_MESSAGE(SceneUpdate);

#undef QUAD_DDS_DISPLAY_MESSAGE

}  // namespace quad::dds
