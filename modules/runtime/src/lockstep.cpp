// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/lockstep.hpp"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "quad/dds/topics.hpp"

namespace quad::runtime {

LockstepReporter::LockstepReporter(dds::Participant& participant, std::string name)
    : name_(std::move(name)), publisher_(participant, dds::topics::kLockstep)
{
}

bool LockstepReporter::reportDone(std::int64_t done_ns)
{
  msg::LockstepReport report;
  report.header().stamp_ns(done_ns);
  report.participant(name_);
  report.done_ns(done_ns);
  if (!publisher_.write(report)) {
    return false;
  }
  reported_ns_ = std::max(reported_ns_, done_ns);
  return true;
}

bool LockstepReporter::reportAhead(std::int64_t done_ns, std::int64_t clock_ns, std::int64_t budget_ns)
{
  return done_ns > reported_ns_ && reported_ns_ < clock_ns + budget_ns / 2 && reportDone(done_ns);
}

void LockstepReporter::holding(std::int64_t clock_ns, const std::function<std::string()>& why)
{
  constexpr std::int64_t kFirstLogNs = 2'000'000'000;
  constexpr std::int64_t kLogPeriodNs = 5'000'000'000;
  const std::int64_t now = common::steadyTimeNs();
  if (clock_ns != holding_clock_ns_) {
    holding_clock_ns_ = clock_ns;
    holding_since_ns_ = now;
    next_holding_log_ns_ = now + kFirstLogNs;
    return;
  }
  if (now >= next_holding_log_ns_) {
    spdlog::warn("lockstep: {} not done up to sim time {:.3f} s after {:.1f} s: {}", name_, common::toSeconds(clock_ns),
                 common::toSeconds(now - holding_since_ns_), why());
    next_holding_log_ns_ = now + kLogPeriodNs;
  }
}

namespace {

/// The ledger's name of `participant` of `vehicle` in a fleet's barrier.
std::string fleetName(std::string_view participant, std::uint32_t vehicle)
{
  return std::string(participant) + " of vehicle " + std::to_string(vehicle);
}

/// The ledger's names: the participants' own, or each of them once per vehicle of a fleet.
std::vector<std::string> ledgerNames(std::vector<std::string> participants, const std::vector<std::uint32_t>& vehicles)
{
  if (vehicles.empty()) {
    return participants;
  }
  std::vector<std::string> names;
  for (const std::uint32_t vehicle : vehicles) {
    for (const std::string& p : participants) {
      names.push_back(fleetName(p, vehicle));
    }
  }
  return names;
}

}  // namespace

LockstepBarrier::LockstepBarrier(dds::Participant& participant, std::vector<std::string> participants,
                                 dds::Waker* waker, std::vector<std::uint32_t> vehicles)
    : vehicles_(std::move(vehicles)),
      ledger_(ledgerNames(std::move(participants), vehicles_)),
      waker_(waker != nullptr ? waker : &own_waker_),
      subscriber_(participant, dds::topics::kLockstep, waker_)
{
}

bool LockstepBarrier::poll(std::int64_t sim_ns)
{
  collect();
  return ledger_.caughtUp(sim_ns);
}

bool LockstepBarrier::worksOnInputsOnly(std::string_view participant)
{
  bool known = true;
  for (const std::string& name : ledgerNames({std::string(participant)}, vehicles_)) {
    known = ledger_.worksOnInputsOnly(name) && known;
  }
  return known;
}

void LockstepBarrier::inputGiven(std::string_view participant, std::uint32_t vehicle, std::int64_t due_ns)
{
  ledger_.inputGiven(vehicles_.empty() ? std::string(participant) : fleetName(participant, vehicle), due_ns);
}

void LockstepBarrier::collect()
{
  for (;;) {
    const auto report = vehicles_.empty() ? subscriber_.take() : subscriber_.takeServed(vehicles_);
    if (!report) {
      break;
    }
    const std::string name = vehicles_.empty() ? report->participant().to_string()
                                               : fleetName(report->participant().to_string(), report->header().vehicle_id());
    const auto outcome = ledger_.report(name, report->done_ns());
    if (outcome != LockstepLedger::Report::kAccepted) {
      ++ignored_;
      spdlog::warn("lockstep: ignored report from '{}' at {} ns: {}", name, report->done_ns(),
                   outcome == LockstepLedger::Report::kUnknownParticipant
                       ? "not an expected participant"
                       : "earlier than its previous report");
    }
  }
}

LockstepBarrier::Result LockstepBarrier::waitUntilDone(std::int64_t sim_ns,
                                                       std::chrono::milliseconds timeout)
{
  const std::int64_t deadline =
      common::steadyTimeNs() + std::chrono::nanoseconds(timeout).count();
  collect();
  while (!ledger_.caughtUp(sim_ns)) {
    if (common::steadyTimeNs() >= deadline) {
      Result result;
      result.late = ledger_.late(sim_ns);
      char head[128];
      std::snprintf(head, sizeof(head), "lockstep: at sim time %.3f s, still waiting after %lld ms for: ",
                    common::toSeconds(sim_ns), static_cast<long long>(timeout.count()));
      result.message = head;
      for (std::size_t i = 0; i < result.late.size(); ++i) {
        result.message += (i == 0 ? "" : ", ") + result.late[i];
      }
      return result;
    }
    waker_->waitUntil(deadline);
    collect();
  }
  return Result{.caught_up = true};
}

}  // namespace quad::runtime
