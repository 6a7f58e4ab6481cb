// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/events.hpp"

#include <algorithm>

namespace quad::dds {

namespace {
constexpr std::size_t kHistoryLimit = 1024;  // bounded: a long run must not grow without end
}

std::string_view toString(EventKind kind)
{
  switch (kind) {
    case EventKind::kMatched:
      return "matched";
    case EventKind::kUnmatched:
      return "unmatched";
    case EventKind::kDeadlineMissed:
      return "deadline missed";
    case EventKind::kLivelinessLost:
      return "liveliness lost";
    case EventKind::kLivelinessRegained:
      return "liveliness regained";
    case EventKind::kIncompatibleQos:
      return "incompatible QoS";
    case EventKind::kTypeMismatch:
      return "type mismatch";
    case EventKind::kSampleLost:
      return "sample lost";
    case EventKind::kSampleRejected:
      return "sample rejected";
    case EventKind::kForeignSample:
      return "sample of another vehicle";
    case EventKind::kWriteFailed:
      return "write failed";
  }
  return "?";
}

void EventQueue::setNotifier(std::function<void()> notifier)
{
  std::lock_guard lock(mutex_);
  notifier_ = std::move(notifier);
}

void EventQueue::push(EndpointEvent event)
{
  std::function<void()> notifier;
  {
    std::lock_guard lock(mutex_);
    history_.push_back(event);
    if (history_.size() > kHistoryLimit) {
      history_.erase(history_.begin());
    }
    events_.push_back(std::move(event));
    if (events_.size() > kHistoryLimit) {
      events_.pop_front();
    }
    notifier = notifier_;
  }
  changed_.notify_all();
  if (notifier) {
    notifier();
  }
}

std::vector<EndpointEvent> EventQueue::drain()
{
  std::lock_guard lock(mutex_);
  std::vector<EndpointEvent> out(std::make_move_iterator(events_.begin()),
                                 std::make_move_iterator(events_.end()));
  events_.clear();
  return out;
}

std::vector<EndpointEvent> EventQueue::waitFor(
    const std::function<bool(const EndpointEvent&)>& match, std::chrono::milliseconds timeout)
{
  std::unique_lock lock(mutex_);
  std::vector<EndpointEvent> found;
  changed_.wait_for(lock, timeout, [&] {
    found.clear();
    std::copy_if(history_.begin(), history_.end(), std::back_inserter(found), match);
    return !found.empty();
  });
  return found;
}

std::string qosPolicyName(std::uint32_t policy_id)
{
  // Ids of the DDS specification (Fast DDS's QosPolicyId_t).
  static const char* const kNames[] = {
      "INVALID",          "USER_DATA",          "DURABILITY",      "PRESENTATION",
      "DEADLINE",         "LATENCY_BUDGET",     "OWNERSHIP",       "OWNERSHIP_STRENGTH",
      "LIVELINESS",       "TIME_BASED_FILTER",  "PARTITION",       "RELIABILITY",
      "DESTINATION_ORDER", "HISTORY",           "RESOURCE_LIMITS", "ENTITY_FACTORY",
      "WRITER_DATA_LIFECYCLE", "READER_DATA_LIFECYCLE", "TOPIC_DATA", "GROUP_DATA",
      "TRANSPORT_PRIORITY", "LIFESPAN",         "DURABILITY_SERVICE", "DATA_REPRESENTATION",
      "TYPE_CONSISTENCY_ENFORCEMENT", "DISABLE_POSITIVE_ACKS"};
  if (policy_id < std::size(kNames)) {
    return kNames[policy_id];
  }
  return "policy " + std::to_string(policy_id);
}

}  // namespace quad::dds
