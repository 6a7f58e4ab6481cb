// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/sim_period_filter.hpp"

#include <charconv>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "quad/common/payload_header.hpp"
#include "quad/common/time.hpp"

namespace quad::dds {

namespace fdds = eprosima::fastdds::dds;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

SimPeriodGate::SimPeriodGate(std::int64_t period_ns) : period_ns_(period_ns)
{
  if (period_ns <= 0) {
    throw std::invalid_argument("a sim-time period of " + std::to_string(period_ns) + " ns: it must be positive");
  }
}

namespace {
/// Floor division: a stamp before 0 (none the plant writes) still has a window of its own.
std::int64_t windowOf(std::int64_t stamp_ns, std::int64_t period_ns)
{
  return stamp_ns / period_ns - (stamp_ns % period_ns < 0 ? 1 : 0);
}
}  // namespace

std::int64_t simPeriodWindowEnd(std::int64_t stamp_ns, std::int64_t period_ns)
{
  return (windowOf(stamp_ns, period_ns) + 1) * period_ns;
}

bool SimPeriodGate::pass(std::uint32_t vehicle_id, std::int64_t stamp_ns)
{
  const std::int64_t window = windowOf(stamp_ns, period_ns_);
  std::lock_guard lock(mutex_);
  const auto [it, first] = passed_.try_emplace(vehicle_id, Passed{window, stamp_ns});
  if (!first && it->second.window == window && it->second.stamp_ns != stamp_ns) {
    return false;
  }
  it->second = {window, stamp_ns};
  return true;
}

namespace {

// Fast DDS's two interfaces have no virtual destructor; their instances here are deleted only
// as what they are (delete_content_filter, the factory's static storage).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"

/// One reader's filter: on the writer's side, one per matched reader that asked for it; on the
/// reader's side, one per reader (a topic of its own).
class SimPeriodFilter final : public fdds::IContentFilter {
public:
  explicit SimPeriodFilter(std::int64_t period_ns) : gate_(period_ns) {}
  std::int64_t period() const { return gate_.period(); }

  bool evaluate(const SerializedPayload& payload, const FilterSampleInfo& /*info*/,
                const GUID_t& /*reader_guid*/) const override
  {
    const auto header = common::payloadHeader(std::span<const std::uint8_t>(payload.data, payload.length));
    return !header || gate_.pass(header->vehicle_id, header->stamp_ns);
  }

private:
  mutable SimPeriodGate gate_;  // evaluate() is const to Fast DDS; what it passed is the filter's state
};

/// The period of a filter's parameters; nothing when they are not one positive integer.
std::optional<std::int64_t> periodOf(const fdds::IContentFilterFactory::ParameterSeq& parameters)
{
  if (parameters.length() != 1 || parameters[0] == nullptr) {
    return std::nullopt;
  }
  const char* text = parameters[0];
  const char* end = text + std::strlen(text);
  std::int64_t period = 0;
  const auto [ptr, ec] = std::from_chars(text, end, period);
  if (ec != std::errc() || ptr != end || period <= 0) {
    return std::nullopt;
  }
  return period;
}

class SimPeriodFilterFactory final : public fdds::IContentFilterFactory {
public:
  ReturnCode_t create_content_filter(const char* /*filter_class_name*/, const char* /*type_name*/,
                                     const fdds::TopicDataType* /*data_type*/, const char* filter_expression,
                                     const ParameterSeq& filter_parameters,
                                     fdds::IContentFilter*& filter_instance) override
  {
    // A null expression updates the parameters of a filter that exists.
    if (filter_expression != nullptr && std::strcmp(filter_expression, kSimPeriodFilterExpression) != 0) {
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    }
    const auto period = periodOf(filter_parameters);
    if (!period) {
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    }
    auto* existing = static_cast<SimPeriodFilter*>(filter_instance);
    if (existing != nullptr && existing->period() == *period) {
      return ReturnCode_t::RETCODE_OK;  // the same filter: what it passed so far still counts
    }
    delete existing;
    filter_instance = new SimPeriodFilter(*period);
    return ReturnCode_t::RETCODE_OK;
  }

  ReturnCode_t delete_content_filter(const char* /*filter_class_name*/, fdds::IContentFilter* filter_instance) override
  {
    delete static_cast<SimPeriodFilter*>(filter_instance);
    return ReturnCode_t::RETCODE_OK;
  }
};

#pragma GCC diagnostic pop

}  // namespace

fdds::IContentFilterFactory& simPeriodFilterFactory()
{
  static SimPeriodFilterFactory factory;
  return factory;
}

fdds::DataReaderQos withMinimumSeparation(fdds::DataReaderQos qos, std::int64_t period_ns)
{
  if (period_ns < 0) {
    throw std::invalid_argument("a minimum separation of " + std::to_string(period_ns) + " ns");
  }
  const auto duration = [](std::int64_t ns) {
    return eprosima::fastrtps::Duration_t(static_cast<std::int32_t>(ns / common::kNanosecondsPerSecond),
                                          static_cast<std::uint32_t>(ns % common::kNanosecondsPerSecond));
  };
  qos.time_based_filter().minimum_separation = duration(period_ns);
  // A sample a period is what the reader now expects: a deadline shorter than two would be
  // missed by design (a wall-time deadline and a sim-time period meet at 1x real time).
  auto& deadline = qos.deadline().period;
  if (period_ns > 0 && deadline != eprosima::fastrtps::c_TimeInfinite && deadline.to_ns() < 2 * period_ns) {
    deadline = duration(2 * period_ns);
  }
  return qos;
}

std::int64_t minimumSeparationNs(const fdds::DataReaderQos& qos)
{
  const auto& separation = qos.time_based_filter().minimum_separation;
  return static_cast<std::int64_t>(separation.seconds) * common::kNanosecondsPerSecond + separation.nanosec;
}

}  // namespace quad::dds
