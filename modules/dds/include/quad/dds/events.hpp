// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What the DDS layer tells a node about its endpoints: matches, missed deadlines, lost
/// liveliness, and the reasons two endpoints that should talk do not (incompatible QoS, a
/// different type). Listener callbacks only push here; the node's loop drains and reacts.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace quad::dds {

enum class EventKind {
  kMatched,            ///< a remote endpoint matched one of ours
  kUnmatched,          ///< a matched remote endpoint went away
  kDeadlineMissed,     ///< no sample within the DEADLINE period (reader or writer side)
  kLivelinessLost,     ///< a matched writer stopped asserting liveliness / ours failed to
  kLivelinessRegained, ///< a writer is alive again
  kIncompatibleQos,    ///< an endpoint on our topic cannot match for a QoS policy
  kTypeMismatch,       ///< an endpoint on our topic has another type name or key kind
  kSampleLost,         ///< the middleware lost samples (best effort gaps, history overflow)
  kSampleRejected,     ///< a sample was rejected for resource limits
  kForeignSample,      ///< a sample for another vehicle (Header.vehicle_id) was ignored
  kWriteFailed,        ///< write() returned an error (e.g. a full KEEP_ALL history)
};

std::string_view toString(EventKind kind);

struct EndpointEvent {
  EventKind kind;
  std::string topic;
  std::string detail;  ///< human-readable reason, names the policy or types involved
  std::int64_t count = 0;  ///< kSampleLost: samples newly lost
};

/// A thread-safe queue of endpoint events, filled by listeners and drained by the node.
class EventQueue {
public:
  /// Called on every push, from the listener's thread: only notify (e.g. wake a loop).
  void setNotifier(std::function<void()> notifier);

  void push(EndpointEvent event);
  std::vector<EndpointEvent> drain();

  /// Waits until an event satisfying `match` is pushed (or already queued), without
  /// consuming others. Returns it, or nothing after `timeout`. For tests and tools.
  std::vector<EndpointEvent> waitFor(const std::function<bool(const EndpointEvent&)>& match,
                                     std::chrono::milliseconds timeout);

private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<EndpointEvent> events_;
  std::vector<EndpointEvent> history_;  // everything ever pushed, for waitFor
  std::function<void()> notifier_;
};

/// Name of a DDS QoS policy id, e.g. "RELIABILITY", for incompatible-QoS reports.
std::string qosPolicyName(std::uint32_t policy_id);

}  // namespace quad::dds
