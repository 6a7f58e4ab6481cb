// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Type-agnostic samples: the serialized payload as bytes (4-byte encapsulation header, then
/// CDR). Registered under a remote type's name with the same key kind, a RawType receives from
/// typed writers and writes to typed readers, so tools (topic echo/pub, the recorder) handle
/// any topic without its generated C++ type.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "quad/dds/endpoint.hpp"

namespace quad::dds {

struct RawSample {
  std::vector<std::uint8_t> payload;
};

/// The vehicle id of a quad message payload (the first member of its leading Header), if the
/// payload is long enough and plain CDR.
std::optional<std::uint32_t> payloadVehicleId(std::span<const std::uint8_t> payload);

class RawType : public eprosima::fastdds::dds::TopicDataType {
public:
  /// `max_size`: the largest payload accepted [bytes].
  RawType(const std::string& type_name, bool keyed, std::uint32_t max_size);

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  /// Keyed types: the quad key (Header.vehicle_id) read from the payload.
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5) override;
};

/// A TypeSupport for a contract's type, sized from the contract.
eprosima::fastdds::dds::TypeSupport rawTypeFor(const TopicInfo& info);

/// Writes raw payloads on a topic.
class RawPublisher : public WriterEndpoint {
public:
  RawPublisher(Participant& participant, const TopicInfo& info,
               std::optional<eprosima::fastdds::dds::DataWriterQos> qos = std::nullopt);
  bool write(RawSample& sample) { return writeSample(&sample); }
};

/// Takes raw payloads from a topic.
class RawSubscriber : public ReaderEndpoint {
public:
  RawSubscriber(Participant& participant, const TopicInfo& info, Waker* waker,
                std::optional<eprosima::fastdds::dds::DataReaderQos> qos = std::nullopt);
  bool take(RawSample& sample) { return takeSample(&sample); }
  /// Also says which writer sent it (an id stable for the writer's life) and when the
  /// middleware received it (wall time, ns).
  bool take(RawSample& sample, std::uint64_t& writer, std::int64_t& received_ns)
  {
    return takeSample(&sample, &writer, &received_ns);
  }
};

}  // namespace quad::dds
