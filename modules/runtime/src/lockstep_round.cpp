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

bool LockstepRound::reportDue(std::int64_t now_ns)
{
  if (now_ns < next_report_ns_) {
    return false;
  }
  next_report_ns_ = now_ns + report_every_ns_;
  return true;
}

}  // namespace quad::runtime
