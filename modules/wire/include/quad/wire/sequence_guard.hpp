// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Refuses a GAP that declares sequence numbers irrelevant far beyond what its writer has
/// written. Fast DDS 2.9's reader walks a GAP's range one sequence number at a time with the
/// reader's lock held, so one bit flipped high in a GAP's list base (2^31 and more numbers)
/// would keep a receive thread busy for minutes, and with it every thread that takes from
/// that reader. Nothing in the datagram's structure shows the damage: the writer's other
/// submessages do.
///
/// Per writer it keeps the highest sequence number its DATA, DATA_FRAG, HEARTBEAT and
/// HEARTBEAT_FRAG stated and when. A GAP reaching more than kSlack + kMaxRate · (time since
/// then) past it is refused (its datagram is dropped; the writer sends the GAP again when
/// the reader asks). A writer first heard through a GAP is not judged. A sequence number that
/// itself leaps past that bound is not believed until the writer's next one continues from it
/// (it really wrote that many while its datagrams did not arrive: a partition, a reader met
/// late), so that a damaged HEARTBEAT cannot open the way for a damaged GAP.

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "quad/wire/rtps_check.hpp"

namespace quad::wire {

class SequenceGuard {
public:
  static constexpr std::int64_t kSlack = 1024;
  static constexpr double kMaxRate = 20000.0;      ///< samples a second: above any writer's rate
  static constexpr std::size_t kMaxWriters = 4096;  ///< forgotten all at once beyond this

  /// The first GAP of one datagram's sequence numbers that leaps; nothing when none does.
  /// `now_ns`: a steady clock.
  std::optional<RtpsDefect> admit(const std::vector<RtpsSequence>& sequences, std::int64_t now_ns);

private:
  struct Track {
    std::int64_t highest = 0;          ///< the highest believed
    std::int64_t at_ns = 0;            ///< when it was stated (0: never)
    std::optional<std::int64_t> leap;  ///< one its next may confirm
  };
  using Key = std::pair<std::array<std::uint8_t, 12>, std::uint32_t>;

  std::mutex mutex_;
  std::map<Key, Track> tracks_;
};

}  // namespace quad::wire
