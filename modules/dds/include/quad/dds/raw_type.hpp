// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Type-agnostic samples: the serialized payload as bytes (4-byte encapsulation header, then
/// CDR). Registered under a remote type's name with the same key kind, a RawType receives from
/// typed writers and writes to typed readers, so tools (topic echo/pub, the recorder) handle
/// any topic without its generated C++ type.

#include <cstdint>
#include <memory>
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

/// The type support a raw endpoint of `info` uses on `participant`: the one registered there
/// under the contract's type name, when another endpoint of the participant registered it
/// typed (a container's modules: one name has one serialisation per participant), else a
/// RawType. A raw endpoint on a typed support converts each sample on its way (TypedPayload).
eprosima::fastdds::dds::TypeSupport payloadTypeFor(Participant& participant, const TopicInfo& info);

/// A typed support's samples as payloads: a sample deserialised from a payload, and one
/// serialised to a payload (the bytes the writer sent, but for CDR's alignment padding, which
/// no reader reads). One typed sample and one payload buffer, reused.
class TypedPayload {
public:
  explicit TypedPayload(eprosima::fastdds::dds::TypeSupport type);
  ~TypedPayload();
  TypedPayload(const TypedPayload&) = delete;
  TypedPayload& operator=(const TypedPayload&) = delete;
  /// The typed sample taken into or written from.
  void* data() { return data_; }
  bool fromPayload(const RawSample& sample);
  bool toPayload(RawSample& sample);

private:
  eprosima::fastdds::dds::TypeSupport type_;
  void* data_;
  eprosima::fastrtps::rtps::SerializedPayload_t payload_;  // grown to the largest sample, never shrunk
};

/// Writes raw payloads on a topic.
class RawPublisher : public WriterEndpoint {
public:
  RawPublisher(Participant& participant, const TopicInfo& info,
               std::optional<eprosima::fastdds::dds::DataWriterQos> qos = std::nullopt);
  bool write(RawSample& sample)
  {
    if (!typed_) {
      return writeSample(&sample);
    }
    return typed_->fromPayload(sample) && writeSample(typed_->data());
  }

private:
  std::unique_ptr<TypedPayload> typed_;  // on a typed support only
};

/// Takes raw payloads from a topic.
class RawSubscriber : public ReaderEndpoint {
public:
  RawSubscriber(Participant& participant, const TopicInfo& info, Waker* waker,
                std::optional<eprosima::fastdds::dds::DataReaderQos> qos = std::nullopt);
  bool take(RawSample& sample) { return take(sample, nullptr, nullptr); }
  /// Also says which writer sent it (an id stable for the writer's life) and when the
  /// middleware received it (wall time, ns).
  bool take(RawSample& sample, std::uint64_t& writer, std::int64_t& received_ns)
  {
    return take(sample, &writer, &received_ns);
  }

private:
  bool take(RawSample& sample, std::uint64_t* writer, std::int64_t* received_ns);
  std::unique_ptr<TypedPayload> typed_;  // on a typed support only
};

}  // namespace quad::dds
