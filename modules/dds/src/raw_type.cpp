// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/raw_type.hpp"

#include <cstring>

#include "quad/common/payload_header.hpp"
#include "quad/dds/message_types.hpp"

namespace quad::dds {

namespace frtps = eprosima::fastrtps::rtps;
namespace fdds = eprosima::fastdds::dds;

std::optional<std::uint32_t> payloadVehicleId(std::span<const std::uint8_t> payload)
{
  const auto header = common::payloadHeader(payload, true);
  return header ? std::optional<std::uint32_t>(header->vehicle_id) : std::nullopt;
}

RawType::RawType(const std::string& type_name, bool keyed, std::uint32_t max_size)
{
  setName(type_name.c_str());
  m_typeSize = max_size;
  m_isGetKeyDefined = keyed;
}

bool RawType::serialize(void* data, frtps::SerializedPayload_t* payload)
{
  const auto& bytes = static_cast<RawSample*>(data)->payload;
  if (bytes.size() < 4 || bytes.size() > payload->max_size) {
    return false;
  }
  std::memcpy(payload->data, bytes.data(), bytes.size());
  payload->length = static_cast<std::uint32_t>(bytes.size());
  payload->encapsulation = bytes[1] == 1 ? CDR_LE : CDR_BE;
  return true;
}

bool RawType::deserialize(frtps::SerializedPayload_t* payload, void* data)
{
  auto& bytes = static_cast<RawSample*>(data)->payload;
  bytes.assign(payload->data, payload->data + payload->length);
  return true;
}

std::function<std::uint32_t()> RawType::getSerializedSizeProvider(void* data)
{
  const auto size = static_cast<std::uint32_t>(static_cast<RawSample*>(data)->payload.size());
  return [size] { return size; };
}

void* RawType::createData() { return new RawSample(); }

void RawType::deleteData(void* data) { delete static_cast<RawSample*>(data); }

bool RawType::getKey(void* data, frtps::InstanceHandle_t* handle, bool /*force_md5*/)
{
  if (!m_isGetKeyDefined) {
    return false;
  }
  const auto id = payloadVehicleId(static_cast<RawSample*>(data)->payload);
  if (!id) {
    return false;
  }
  vehicleKeyHash(*id, *handle);
  return true;
}

fdds::TypeSupport rawTypeFor(const TopicInfo& info)
{
  return fdds::TypeSupport(new RawType(std::string(info.type_name), info.has_header,
                                       info.max_serialized_size != nullptr
                                           ? info.max_serialized_size()
                                           : 64U * 1024U * 1024U));
}

fdds::TypeSupport payloadTypeFor(Participant& participant, const TopicInfo& info)
{
  fdds::TypeSupport registered = participant.raw()->find_type(std::string(info.type_name));
  return registered.empty() ? rawTypeFor(info) : registered;
}

namespace {
// Raw samples vary in size: allocate per sample instead of preallocating the maximum.
template <class Qos>
Qos dynamicMemory(Qos qos)
{
  qos.endpoint().history_memory_policy = frtps::DYNAMIC_REUSABLE_MEMORY_MODE;
  return qos;
}

/// A TypedPayload when `type` is not a RawType.
std::unique_ptr<TypedPayload> typedPayload(const fdds::TypeSupport& type)
{
  return dynamic_cast<const RawType*>(type.get()) != nullptr ? nullptr : std::make_unique<TypedPayload>(type);
}
}  // namespace

TypedPayload::TypedPayload(fdds::TypeSupport type) : type_(std::move(type)), data_(type_->createData()) {}

TypedPayload::~TypedPayload() { type_->deleteData(data_); }

bool TypedPayload::fromPayload(const RawSample& sample)
{
  const auto size = static_cast<std::uint32_t>(sample.payload.size());
  payload_.reserve(size);  // grows only
  std::memcpy(payload_.data, sample.payload.data(), size);
  payload_.length = size;
  payload_.pos = 0;
  return type_->deserialize(&payload_, data_);
}

bool TypedPayload::toPayload(RawSample& sample)
{
  payload_.reserve(type_->getSerializedSizeProvider(data_)());  // grows only
  payload_.length = 0;
  payload_.pos = 0;
  if (!type_->serialize(data_, &payload_)) {
    return false;
  }
  sample.payload.assign(payload_.data, payload_.data + payload_.length);
  return true;
}

RawPublisher::RawPublisher(Participant& participant, const TopicInfo& info,
                           std::optional<fdds::DataWriterQos> qos)
    : WriterEndpoint(participant, info, payloadTypeFor(participant, info),
                     dynamicMemory(qos ? *qos : participant.writerQos(info))),
      typed_(typedPayload(payloadTypeFor(participant, info)))
{
}

RawSubscriber::RawSubscriber(Participant& participant, const TopicInfo& info, Waker* waker,
                             std::optional<fdds::DataReaderQos> qos)
    : ReaderEndpoint(participant, info, payloadTypeFor(participant, info), waker,
                     dynamicMemory(qos ? *qos : participant.readerQos(info))),
      typed_(typedPayload(payloadTypeFor(participant, info)))
{
}

bool RawSubscriber::take(RawSample& sample, std::uint64_t* writer, std::int64_t* received_ns)
{
  if (!typed_) {
    return takeSample(&sample, writer, received_ns);
  }
  // A sample the typed support cannot serialise again is taken and left out.
  while (takeSample(typed_->data(), writer, received_ns)) {
    if (typed_->toPayload(sample)) {
      return true;
    }
  }
  return false;
}

}  // namespace quad::dds
