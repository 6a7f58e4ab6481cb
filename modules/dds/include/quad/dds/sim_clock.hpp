// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Following the plant's clock (quad/sim/clock), as every reader of it must: sim time only
/// moves forward whatever order samples arrive in, and the newest sample tells whether the run
/// is in lockstep, how many depth frames the plant has published and whether a vehicle state of
/// the clock's time was sent. With it, the check that a vehicle state is not stamped further
/// past the clock than the plant sends one. Nodes follow it through Node::followSimClock().

#include <cstdint>
#include <vector>

#include <quad/msg/SimClock.h>

#include "quad/dds/subscriber.hpp"

namespace quad::dds {

class SimClockFollower {
public:
  /// Follows the clock of the participant's own vehicle, or with `served` the clock samples
  /// of those vehicles (the launcher following a fleet: one clock, a sample per vehicle).
  SimClockFollower(Participant& participant, Waker* waker = nullptr, std::vector<std::uint32_t> served = {});

  /// Takes every clock sample that arrived; true when one did.
  bool update();

  bool seen() const { return seen_; }                         ///< a clock sample arrived
  bool lockstep() const { return lockstep_; }                 ///< of the newest sample
  std::int64_t ns() const { return ns_; }                     ///< [ns] newest sim time; 0 before any
  std::uint64_t depthFrames() const { return depth_frames_; }  ///< published up to then
  bool stateSent() const { return state_sent_; }              ///< of the newest sample

  /// A vehicle state stamped `stamp_ns` is no further past the newest clock than the plant
  /// sends one (topics::kStateAheadOfClockNs): the plant sends both each step on separate
  /// topics. One further ahead is a bad input: taken, it would make every true state after it
  /// look out of order.
  bool vouchesFor(std::int64_t stamp_ns) const;

private:
  Subscriber<msg::SimClock> clock_;
  std::vector<std::uint32_t> served_;
  bool seen_ = false;
  bool lockstep_ = false;
  std::int64_t ns_ = 0;
  std::uint64_t depth_frames_ = 0;
  bool state_sent_ = true;
};

}  // namespace quad::dds
