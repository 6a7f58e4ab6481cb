// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Following the plant's clock (quad/sim/clock), as every reader of it must: sim time only
/// moves forward whatever order samples arrive in, and the newest sample tells whether the run
/// is in lockstep, how many depth frames the plant has published and whether a vehicle state of
/// the clock's time was sent. With it, the check that a vehicle state is not stamped further
/// past the clock than the plant sends one. Nodes follow it through Node::followSimClock().

#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <quad/msg/SimClock.h>

#include "quad/dds/subscriber.hpp"

namespace quad::runtime {

class SimClockFollower {
public:
  /// Follows the clock of the participant's own vehicle, or with `served` the clock samples
  /// of those vehicles (the launcher following a fleet: one clock, a sample per vehicle).
  /// `depth` > 0: the reader keeps that many unread samples, not the newest only, so that a
  /// follower that works while the clock runs on still takes every sample.
  SimClockFollower(dds::Participant& participant, dds::Waker* waker = nullptr, std::vector<std::uint32_t> served = {},
                   std::int32_t depth = 0);

  /// An onlooker's follower (the launcher's observer): the newest sample only, one per
  /// `period_ns` of sim time, best effort. A sample lost or left out is replaced by the next,
  /// and a reader in another process costs the plant one datagram a period instead of two a
  /// step (a reliable writer follows each sample of a keep-last-one history with a heartbeat).
  /// Not for a node the lockstep clock waits for, which must see every step it answers.
  static SimClockFollower onlooker(dds::Participant& participant, std::vector<std::uint32_t> served,
                                   std::int64_t period_ns);

  /// Takes every clock sample that arrived; true when one did.
  bool update();

  bool seen() const { return seen_; }                         ///< a clock sample arrived
  bool lockstep() const { return lockstep_; }                 ///< of the newest sample
  std::int64_t ns() const { return ns_; }                     ///< [ns] newest sim time; 0 before any
  std::uint64_t depthFrames() const { return depth_frames_; }  ///< published up to then
  bool stateSent() const { return state_sent_; }              ///< of the newest sample
  /// Depth frames published up to sim time `ns`, as the newest clock sample taken at or before
  /// it counted them (0 before the first). Kept for the last kHistoryNs of sim time.
  std::uint64_t depthFramesAt(std::int64_t ns) const;
  /// False when a sample of sim time `ns` was taken that said no vehicle state of that time
  /// was sent (a fault dropped it); true otherwise. Kept for the last kHistoryNs of sim time.
  bool stateSentAt(std::int64_t ns) const;
  /// [ns] The newest sim time whose sample said a vehicle state of that time was sent (-1:
  /// none yet): a reader that handled its states up to then has every state sent so far.
  std::int64_t lastStateSentNs() const { return last_sent_ns_; }
  static constexpr std::int64_t kHistoryNs = 2'000'000'000;

  /// A vehicle state stamped `stamp_ns` is no further past the newest clock than the plant
  /// sends one (topics::kStateAheadOfClockNs): the plant sends both each step on separate
  /// topics. One further ahead is a bad input: taken, it would make every true state after it
  /// look out of order.
  bool vouchesFor(std::int64_t stamp_ns) const;

private:
  SimClockFollower(dds::Participant& participant, dds::Waker* waker, std::vector<std::uint32_t> served,
                   std::optional<eprosima::fastdds::dds::DataReaderQos> qos);

  dds::Subscriber<msg::SimClock> clock_;
  std::vector<std::uint32_t> served_;
  bool seen_ = false;
  bool lockstep_ = false;
  std::int64_t ns_ = 0;
  std::uint64_t depth_frames_ = 0;
  std::deque<std::pair<std::int64_t, std::uint64_t>> frames_by_ns_;  // (sample's time, count) where the count rose
  std::deque<std::int64_t> unsent_ns_;  // times of the samples that said no state was sent
  bool state_sent_ = true;
  std::int64_t last_sent_ns_ = -1;
};

}  // namespace quad::runtime
