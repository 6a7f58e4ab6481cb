// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Lockstep over DDS (DESIGN.md §5). A lockstep participant reports "done up to sim time t"
/// with a LockstepReporter; the clock owner waits with a LockstepBarrier before advancing.

#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <quad/msg/LockstepReport.h>

#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/runtime/lockstep_ledger.hpp"

namespace quad::runtime {

/// The lockstep name of a run's recorder. It holds only the run's start: once it reads every
/// topic the clock owner writes, it reports itself done up to kDoneForGoodNs.
inline constexpr const char* kRecorderParticipant = "record";
/// The lockstep name of a run's observer (the launcher's participant). It too holds only the
/// run's start: once it reads the states and clock samples it scores, it reports itself done
/// up to kDoneForGoodNs.
inline constexpr const char* kObserverParticipant = "launch";
/// The lockstep name of a vehicle's mapper. Its work comes from the depth frames the clock
/// owner writes, each due the map's budget after its stamp (LockstepBarrier::inputGiven).
inline constexpr const char* kMapperParticipant = "mapping";
/// A report's done_ns from a participant that will never hold the clock again.
inline constexpr std::int64_t kDoneForGoodNs = std::numeric_limits<std::int64_t>::max();

/// Publishes this participant's progress on quad/sim/lockstep.
class LockstepReporter {
public:
  /// `name` must be one the clock owner's barrier expects.
  LockstepReporter(dds::Participant& participant, std::string name);

  /// Reports that the work due up to `done_ns` of sim time is finished.
  bool reportDone(std::int64_t done_ns);

  /// Reports `done_ns` (reportDone) when it is newer than the last report and the clock may
  /// soon need it: with no budget every time the clock (`clock_ns`) passed the last report;
  /// with one, once the clock came within half of `budget_ns` of it. A participant whose
  /// outputs are due a budget after their inputs, and so reports ahead of the clock, then
  /// reports a few times a budget, not every round, and the clock still never waits for a
  /// report of work that is done. True when a report went out.
  bool reportAhead(std::int64_t done_ns, std::int64_t clock_ns, std::int64_t budget_ns);

  /// Says that the work due up to `clock_ns` is not finished, and why (called only when it is
  /// logged). Once the clock has waited for this participant for 2 s of wall time, logs
  /// "lockstep: <name> not done up to ...: <why>" every 5 s, so a stalled run says who holds
  /// it and on what.
  void holding(std::int64_t clock_ns, const std::function<std::string()>& why);

  /// The newest done time reported (-1: none yet).
  std::int64_t reportedNs() const { return reported_ns_; }
  int matchedBarriers() const { return publisher_.matchedReaders(); }

private:
  std::string name_;
  dds::Publisher<msg::LockstepReport> publisher_;
  std::int64_t reported_ns_ = -1;  // the newest done time reported (-1: none yet)
  std::int64_t holding_clock_ns_ = -1;  // the clock time held since holding_since_ns_ (wall)
  std::int64_t holding_since_ns_ = 0;
  std::int64_t next_holding_log_ns_ = 0;
};

/// The clock owner's side: collects reports and waits until everyone caught up.
class LockstepBarrier {
public:
  /// `waker` (optional) is notified when reports arrive, for a caller that polls from its own
  /// loop instead of blocking in waitUntilDone. `vehicles` (a clock owner that simulates a
  /// fleet): each of the participants is expected once per vehicle, its reports told apart by
  /// their header's vehicle id and named "mapping of vehicle 2"; empty: once, for this
  /// participant's vehicle.
  LockstepBarrier(dds::Participant& participant, std::vector<std::string> participants,
                  dds::Waker* waker = nullptr, std::vector<std::uint32_t> vehicles = {});

  struct Result {
    bool caught_up = false;
    /// Empty when caught up; else "lockstep: at sim time 1.204 s, still waiting after
    /// 2000 ms for: mapping (done up to 1.200 s), control (no report yet)".
    std::string message;
    std::vector<std::string> late;
  };

  /// Blocks until every participant reported done up to `sim_ns`, or `timeout` passes.
  Result waitUntilDone(std::int64_t sim_ns, std::chrono::milliseconds timeout);

  /// Non-blocking: takes the reports that arrived and says whether everyone is done up to
  /// `sim_ns`.
  bool poll(std::int64_t sim_ns);

  /// `participant` (each vehicle's, in a fleet's barrier) works only on the inputs this clock
  /// owner gives it (LockstepLedger::worksOnInputsOnly). False when it is not one expected.
  bool worksOnInputsOnly(std::string_view participant);
  /// An input given to `participant` of `vehicle` (its id; ignored outside a fleet's barrier),
  /// its work due at `due_ns` (LockstepLedger::inputGiven).
  void inputGiven(std::string_view participant, std::uint32_t vehicle, std::int64_t due_ns);

  /// Reports ignored so far (unknown participant or time going backwards).
  std::uint64_t ignoredReports() const { return ignored_; }
  const LockstepLedger& ledger() const { return ledger_; }

private:
  void collect();

  std::vector<std::uint32_t> vehicles_;  // a fleet's: reports named per vehicle; empty: this participant's
  LockstepLedger ledger_;
  dds::Waker own_waker_;
  dds::Waker* waker_;  // the one the subscriber notifies: the caller's, or own_waker_
  dds::Subscriber<msg::LockstepReport> subscriber_;
  std::uint64_t ignored_ = 0;
};

}  // namespace quad::runtime
