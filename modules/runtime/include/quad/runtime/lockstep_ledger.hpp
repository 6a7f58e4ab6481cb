// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Bookkeeping of lockstep (DESIGN.md §5): sim time may advance to t only when every lockstep
/// participant has reported its work due up to t as done. Pure logic; the DDS helpers in
/// quad/runtime/lockstep.hpp feed it.

#include <cstdint>
#include <deque>
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

  /// Declares that `participant` works only on inputs this clock owner gives it, each with a
  /// due time (the mapper on the depth frames the plant writes, due the map's budget after
  /// their stamp). Once it reported done up to the due time of every input given, it has no
  /// work before the next input's due time: it is done up to then without a report, however
  /// far the clock runs on. Before its first report it is late like any other. False for an
  /// unknown name.
  bool worksOnInputsOnly(std::string_view participant);

  /// An input given to a participant declared worksOnInputsOnly, its work due at `due_ns`
  /// (inputs may come in any order of due times). Ignored for other participants and for an
  /// input the participant already reported done up to. False for an unknown name.
  bool inputGiven(std::string_view participant, std::int64_t due_ns);

  /// True when every participant is done up to at least `sim_ns`.
  bool caughtUp(std::int64_t sim_ns) const;

  /// Participants not yet done up to `sim_ns`, in declaration order.
  std::vector<std::string> lateNames(std::int64_t sim_ns) const;
  /// The same, each with how far it is ("mapping (done up to 1.200 s)" or "control (no report
  /// yet)").
  std::vector<std::string> late(std::int64_t sim_ns) const;

  /// Last reported time of a participant, if any.
  std::optional<std::int64_t> doneNs(std::string_view participant) const;
  /// The time a participant is done up to: its last report, or for one that works on inputs
  /// only and reported every input given done, just before the next one's due time (the
  /// largest time when none is outstanding). None before its first report.
  std::optional<std::int64_t> doneUpToNs(std::string_view participant) const;

  /// The earliest time every participant is done up to (doneUpToNs), if all have reported.
  std::optional<std::int64_t> minimumDoneNs() const;

  const std::vector<std::string>& participants() const { return order_; }

private:
  struct Entry {
    std::optional<std::int64_t> done;  // the newest report
    bool inputs_only = false;
    std::deque<std::int64_t> outstanding;  // inputs_only: due times of inputs given, past the report, rising
  };
  static std::optional<std::int64_t> doneUpTo(const Entry& e);

  std::vector<std::string> order_;
  std::map<std::string, Entry, std::less<>> entries_;
};

}  // namespace quad::runtime
