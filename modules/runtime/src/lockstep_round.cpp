// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/lockstep_round.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace quad::runtime {

LockstepRound::LockstepRound(std::int64_t period_ns, std::int64_t report_every_ns)
    : period_ns_(period_ns), report_every_ns_(report_every_ns)
{
  if (period_ns <= 0 || report_every_ns <= 0) {
    throw std::invalid_argument("a lockstep round of " + std::to_string(period_ns) + " ns of sim time, reported every " +
                                std::to_string(report_every_ns) + " ns: both must be positive");
  }
}

std::int64_t LockstepRound::open(std::int64_t sim_ns, std::int64_t now_ns)
{
  if (!open_) {
    open_ = true;
    end_ns_ = sim_ns + period_ns_;
    wait_since_ns_ = now_ns;
    next_report_ns_ = now_ns + report_every_ns_;
    resend_after_ns_ = kFirstResendNs;
  }
  return start();
}

void LockstepRound::resent(std::int64_t now_ns)
{
  published_ns_ = now_ns;
  if (start() > 0) {
    resend_after_ns_ = std::min(2 * resend_after_ns_, kMaxResendNs);
  }
}

void LockstepRound::waitingFor(std::int64_t now_ns, std::vector<std::string> late)
{
  // A name given twice (the command's "control" and a participant of that name) is one wait.
  std::sort(late.begin(), late.end());
  late.erase(std::unique(late.begin(), late.end()), late.end());
  if (!waiting_) {
    // The first check: those late now were late since the round opened.
    waiting_ = true;
    checked_ns_ = wait_since_ns_;
    late_ = late;
  }
  countWait(now_ns);
  for (const std::string& name : late) {
    if (std::find(late_in_round_.begin(), late_in_round_.end(), name) == late_in_round_.end()) {
      late_in_round_.push_back(name);
    }
  }
  late_ = std::move(late);
}

void LockstepRound::inputsIn(std::int64_t now_ns)
{
  if (!waiting_) {
    return;
  }
  countWait(now_ns);
  for (const std::string& name : late_in_round_) {
    ++waits_[name].rounds;
  }
  ++rounds_waited_;
  waiting_ = false;
  late_.clear();
  late_in_round_.clear();
}

void LockstepRound::countWait(std::int64_t now_ns)
{
  const std::int64_t interval = std::max<std::int64_t>(0, now_ns - checked_ns_);
  for (const std::string& name : late_) {
    waits_[name].wall_ns += interval;
  }
  waited_wall_ns_ += interval;
  checked_ns_ = std::max(checked_ns_, now_ns);
}

bool LockstepRound::reportDue(std::int64_t now_ns)
{
  if (now_ns < next_report_ns_) {
    return false;
  }
  next_report_ns_ = now_ns + report_every_ns_;
  return true;
}

}  // namespace quad::runtime
