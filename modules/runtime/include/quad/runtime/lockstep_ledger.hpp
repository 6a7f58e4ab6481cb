// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Bookkeeping of lockstep (DESIGN.md §5): sim time may advance to t only when every lockstep
/// participant has reported its work due up to t as done. Pure logic; the DDS helpers in
/// quad/runtime/lockstep.hpp feed it.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace quad::runtime {

class LockstepLedger {
public:
  /// The participants the clock owner waits for; names must be unique and non-empty
  /// (throws std::invalid_argument otherwise).
  explicit LockstepLedger(std::vector<std::string> participants);

  enum class Report {
    kAccepted,
    kUnknownParticipant,  ///< not one of the expected names: ignored
    kWentBackwards,       ///< earlier than a previous report of the same participant: ignored
  };

  /// Records that `participant` finished its work up to `done_ns` of sim time.
  Report report(std::string_view participant, std::int64_t done_ns);

  /// True when every participant is done up to at least `sim_ns`.
  bool caughtUp(std::int64_t sim_ns) const;

  /// Participants not yet done up to `sim_ns`, in declaration order.
  std::vector<std::string> lateNames(std::int64_t sim_ns) const;
  /// The same, each with how far it is ("mapping (done up to 1.200 s)" or "control (no report
  /// yet)").
  std::vector<std::string> late(std::int64_t sim_ns) const;

  /// Last reported time of a participant, if any.
  std::optional<std::int64_t> doneNs(std::string_view participant) const;

  /// The earliest time every participant is done up to, if all have reported.
  std::optional<std::int64_t> minimumDoneNs() const;

  const std::vector<std::string>& participants() const { return order_; }

private:
  std::vector<std::string> order_;
  std::map<std::string, std::optional<std::int64_t>, std::less<>> done_;
};

}  // namespace quad::runtime
