// SPDX-License-Identifier: BSD-3-Clause
// A participant's QoS: the loaded profiles' classes, each topic's contract deadline, a
// reader's depth and minimum separation.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "quad/common/payload_header.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/sim_period_filter.hpp"

namespace quad::dds {

namespace fdds = eprosima::fastdds::dds;

namespace {
/// Reads `<class>.<role>` from the loaded profiles; data-sharing off for UDP-only runs, or
/// local peers would bypass UDP through shared memory.
template <class Qos, class Entity, class Getter>
Qos profileQos(Entity* entity, Getter getter, std::string_view qos_class, const char* role,
               const ParticipantOptions& options)
{
  const std::string profile = std::string(qos_class) + "." + role;
  Qos qos;
  if ((entity->*getter)(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("QoS profiles file " + options.qos_file.string() + " has no " +
                             role + " profile '" + profile + "'");
  }
  if (options.transport == Transport::kUdp) {
    qos.data_sharing().off();
  }
  // An instance per vehicle (the key is Header.vehicle_id), for as many as a fleet may have;
  // the history's bound on samples grows with it, or Fast DDS would find the limits
  // inconsistent (fewer samples than instances times samples per instance).
  auto& limits = qos.resource_limits();
  limits.max_instances = common::kMaxFleetVehicles;
  if (limits.max_samples > 0 && limits.max_samples_per_instance > 0) {
    limits.max_samples = std::max(limits.max_samples, limits.max_instances * limits.max_samples_per_instance);
  }
  return qos;
}
}  // namespace

fdds::DataWriterQos SharedParticipant::writerQos(std::string_view qos_class) const
{
  return profileQos<fdds::DataWriterQos>(own_publisher_, &fdds::Publisher::get_datawriter_qos_from_profile, qos_class, "writer", options_);
}

bool SharedParticipant::promisesEverySample(std::string_view qos_class) const
{
  const auto qos = writerQos(qos_class);
  return qos.reliability().kind == fdds::RELIABLE_RELIABILITY_QOS && qos.history().kind == fdds::KEEP_ALL_HISTORY_QOS;
}

fdds::DataReaderQos SharedParticipant::readerQos(std::string_view qos_class) const
{
  auto qos = profileQos<fdds::DataReaderQos>(own_subscriber_, &fdds::Subscriber::get_datareader_qos_from_profile,
                                             qos_class, "reader", options_);
  // With inline keys, writers send each sample's key hash, which the validating transport
  // compares with the key in the payload (wire::checkRtpsDatagram): a damaged key is
  // refused before Fast DDS files the sample under an instance it invents.
  qos.expects_inline_qos(options_.inline_keys);
  return qos;
}

namespace {
/// The contract's deadline as the endpoint's DEADLINE period, unless its class asks a tighter one.
template <class Qos>
Qos withContractDeadline(Qos qos, const TopicInfo& info)
{
  if (info.stale_after_s > 0.0) {
    const eprosima::fastrtps::Duration_t contract(info.stale_after_s);
    if (contract < qos.deadline().period) {
      qos.deadline().period = contract;
    }
  }
  return qos;
}
}  // namespace

fdds::DataWriterQos SharedParticipant::writerQos(const TopicInfo& info) const
{
  return withContractDeadline(writerQos(info.qos_profile), info);
}

fdds::DataReaderQos SharedParticipant::readerQos(const TopicInfo& info) const
{
  // A reader asks for what the contract says: a class's tighter deadline (the state's two
  // periods) is the writers' to offer, not a staleness a reader should act on.
  fdds::DataReaderQos qos = readerQos(info.qos_profile);
  if (info.stale_after_s > 0.0) {
    qos.deadline().period = eprosima::fastrtps::Duration_t(info.stale_after_s);
  }
  return qos;
}

std::optional<fdds::DataReaderQos> readerQosWith(Participant& participant, const TopicInfo& topic, std::int32_t depth,
                                                 std::int64_t period_ns)
{
  if (depth <= 0 && period_ns <= 0) {
    return std::nullopt;
  }
  auto qos = withDepth(participant.readerQos(topic), depth);
  return period_ns > 0 ? withMinimumSeparation(std::move(qos), period_ns) : qos;
}

fdds::DataReaderQos withDepth(fdds::DataReaderQos qos, std::int32_t depth)
{
  if (qos.history().kind != fdds::KEEP_LAST_HISTORY_QOS || qos.history().depth >= depth) {
    return qos;
  }
  qos.history().depth = depth;
  auto& limits = qos.resource_limits();
  if (limits.max_samples_per_instance > 0 && limits.max_samples_per_instance < depth) {
    limits.max_samples_per_instance = depth;
  }
  const std::int32_t needed = limits.max_samples_per_instance * std::max(1, limits.max_instances);
  if (limits.max_samples > 0 && limits.max_samples < needed) {
    limits.max_samples = needed;
  }
  return qos;
}
}  // namespace quad::dds
