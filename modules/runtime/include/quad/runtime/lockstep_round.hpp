// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The clock owner's lockstep round (DESIGN.md §5), without the middleware: the sim time the
/// open round runs to, and, while it waits for the round's inputs (the controller's command,
/// the participants' reports: LockstepBarrier), when to send the round's samples again and
/// when to say whom it waits for. Wall times are CLOCK_MONOTONIC [ns], given by the caller.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace quad::runtime {

class LockstepRound {
public:
  /// `period_ns`: the sim time a round spans; `report_every_ns`: the wall time between two
  /// reports of one wait.
  LockstepRound(std::int64_t period_ns, std::int64_t report_every_ns);

  /// Opens a round from `sim_ns` unless one is open, its wait starting at `now_ns`; the open
  /// round's start [ns of sim time].
  std::int64_t open(std::int64_t sim_ns, std::int64_t now_ns);
  std::int64_t start() const { return end_ns_ - period_ns_; }
  std::int64_t end() const { return end_ns_; }  ///< [ns of sim time] where the round stops
  /// The round ran to its end: the next open() starts another.
  void close() { open_ = false; }

  /// The round's samples went out at `now_ns` (a step published them): a resend is timed from
  /// then.
  void published(std::int64_t now_ns) { published_ns_ = now_ns; }
  /// While the round waits: whether its samples are to go out again now. A sample lost in
  /// transport, or sent before a participant matched, would stall the round for good: they go
  /// again 20 ms into a wait, then (past the first round, the start-up, whose inputs went out
  /// before the modules matched) after twice the last interval each time, up to 0.64 s, so
  /// that a wait that lasts because the machine is overloaded is not made longer by ever more
  /// repeats.
  bool resendDue(std::int64_t now_ns) const { return now_ns - published_ns_ >= resend_after_ns_; }
  /// They went out again at `now_ns`.
  void resent(std::int64_t now_ns);
  static constexpr std::int64_t kFirstResendNs = 20'000'000;
  static constexpr std::int64_t kMaxResendNs = 640'000'000;

  /// While the round waits: true once every `report_every_ns` of it (the first that long after
  /// it began), when the caller says whom it waits for.
  bool reportDue(std::int64_t now_ns);
  /// [ns of wall time] How long the round has waited at `now_ns`.
  std::int64_t waitedNs(std::int64_t now_ns) const { return now_ns - wait_since_ns_; }

  /// Whom the clock waited for, and how long. While the round waits, at `now_ns`: the
  /// participants it waits for then (names: "control" for the command, a barrier's
  /// participants). The wall time since the last call counts to each one it waited for then
  /// (the caller checks again whenever an input comes, so one done meanwhile was done at its
  /// end), and at the first call the time since the round opened to each one late now.
  void waitingFor(std::int64_t now_ns, std::vector<std::string> late);
  /// The round's inputs are all in at `now_ns`: the wait since the last waitingFor() counts too,
  /// and the round to each participant it waited for.
  void inputsIn(std::int64_t now_ns);
  /// Since waitingFor() and before inputsIn(): the round is waiting.
  bool waiting() const { return waiting_; }
  struct Wait {
    std::uint64_t rounds = 0;   ///< rounds that waited for it
    std::int64_t wall_ns = 0;   ///< [ns] wall time they waited for it
  };
  /// Every participant the clock waited for so far.
  const std::map<std::string, Wait, std::less<>>& waits() const { return waits_; }
  std::uint64_t roundsWaited() const { return rounds_waited_; }
  std::int64_t waitedWallNs() const { return waited_wall_ns_; }  ///< [ns] in all

private:
  /// The wall time from the last check to `now_ns` to each participant late at that check.
  void countWait(std::int64_t now_ns);

  std::int64_t period_ns_;
  std::int64_t report_every_ns_;
  bool open_ = false;
  std::int64_t end_ns_ = 0;
  std::int64_t wait_since_ns_ = 0;
  std::int64_t next_report_ns_ = 0;
  std::int64_t published_ns_ = 0;
  std::int64_t resend_after_ns_ = kFirstResendNs;
  bool waiting_ = false;
  std::int64_t checked_ns_ = 0;        // the last waitingFor()
  std::vector<std::string> late_;      // then
  std::vector<std::string> late_in_round_;  // at any check of the round
  std::map<std::string, Wait, std::less<>> waits_;
  std::uint64_t rounds_waited_ = 0;
  std::int64_t waited_wall_ns_ = 0;
};

}  // namespace quad::runtime
