// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Tames RTPS counts that leap. A receiver ignores every HEARTBEAT (HEARTBEAT_FRAG, ACKNACK,
/// NACK_FRAG) whose count is not above the highest it took from that sender, so one datagram
/// with a bit flipped high in a count, damaged on the way or forged, silences the sender for
/// good: a writer's heartbeats then no longer assert its liveliness or trigger repairs (seen:
/// a HEARTBEAT count of 268,435,484 from a writer at 28 made a module's liveliness flap every
/// 0.5 s for the rest of the run).
///
/// A count more than kSlack + kMaxRate · (time since the sender's last count) above the
/// highest passed on is a leap: the datagram goes on with the count lowered to one above that
/// highest, so the receiver still takes it and the sender's next counts still rise above it.
/// A sender whose next count continues from the leap (it really sent that many while its
/// datagrams did not arrive: a burst of fragments overflowing a socket buffer, a partition)
/// is followed there. Nothing is dropped.

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>
#include <vector>

#include "quad/wire/rtps_check.hpp"

namespace quad::wire {

class CountGuard {
public:
  static constexpr std::uint32_t kSlack = 64;
  static constexpr double kMaxRate = 1000.0;  ///< counts a second: above any writer's heartbeat rate
  static constexpr std::size_t kMaxSenders = 4096;  ///< forgotten all at once beyond this

  /// A count to write over a leaping one.
  struct Taming {
    RtpsCount count;         ///< as received (offset, byte order, leaping value)
    std::uint32_t replaced;  ///< the value to pass on instead
    /// The sender's first count: one that joins a running writer (whose counts began at its
    /// start) looks like a leap, and usually is none.
    bool first = false;
  };

  /// The counts of one datagram to lower before it is passed on (none, nearly always).
  /// `now_ns`: a steady clock.
  std::vector<Taming> admit(const std::vector<RtpsCount>& counts, std::int64_t now_ns);

  /// Writes each taming's value over its count in `datagram` (a copy of what was received).
  static void apply(const std::vector<Taming>& tamings, std::uint8_t* datagram);

private:
  struct Track {
    std::uint32_t highest = 0;          ///< the highest count passed on
    std::int64_t at_ns = 0;             ///< when the last count came (0: never)
    std::optional<std::uint32_t> leap;  ///< a leap its next count may confirm
  };
  using Key = std::tuple<std::uint8_t, std::array<std::uint8_t, 12>, std::uint32_t, std::uint32_t>;

  std::mutex mutex_;
  std::map<Key, Track> tracks_;
};

}  // namespace quad::wire
