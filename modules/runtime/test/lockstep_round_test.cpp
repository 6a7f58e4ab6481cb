// SPDX-License-Identifier: BSD-3-Clause
// The clock owner's round: the sim time it spans, and while it waits, when its samples go out
// again and when the wait is reported.
#include "quad/runtime/lockstep_round.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace quad::runtime {
namespace {

constexpr std::int64_t kPeriod = 4'000'000;
constexpr std::int64_t kReportEvery = 5'000'000'000;
constexpr std::int64_t kMs = 1'000'000;

/// The wall times [ms from the wait's start] at which a round that never ends sends its
/// samples again, polled every millisecond for `wait_ms`.
std::vector<std::int64_t> resends(LockstepRound& round, std::int64_t wait_ms)
{
  std::vector<std::int64_t> at;
  for (std::int64_t ms = 0; ms <= wait_ms; ++ms) {
    if (round.resendDue(ms * kMs)) {
      round.resent(ms * kMs);
      at.push_back(ms);
    }
  }
  return at;
}

TEST(LockstepRound, ARoundSpansThePeriodFromTheTimeItOpenedUntilItCloses)
{
  LockstepRound round(kPeriod, kReportEvery);
  EXPECT_EQ(round.open(8 * kMs, 0), 8 * kMs);
  EXPECT_EQ(round.end(), 12 * kMs);
  EXPECT_EQ(round.open(10 * kMs, 1), 8 * kMs);  // open: the same round, whatever the clock says
  round.close();
  EXPECT_EQ(round.open(12 * kMs, 2), 12 * kMs);
  EXPECT_EQ(round.end(), 16 * kMs);
}

TEST(LockstepRound, ItsSamplesGoAgainEvery20MsInTheFirstRoundThenTwiceAsLateEachTimeUpTo640Ms)
{
  // The first round (sim time 0): its inputs went out before the modules matched, and the
  // controller arms in wall time: a repeat every 20 ms for as long as it takes.
  LockstepRound first(kPeriod, kReportEvery);
  first.open(0, 0);
  first.published(0);
  EXPECT_EQ(resends(first, 100), (std::vector<std::int64_t>{20, 40, 60, 80, 100}));

  // Later rounds back off: 20, 40, 80, ... ms apart, never more than 640.
  LockstepRound later(kPeriod, kReportEvery);
  later.open(kPeriod, 0);
  later.published(0);
  const auto at = resends(later, 3'000);
  EXPECT_EQ(std::vector<std::int64_t>(at.begin(), at.begin() + 6), (std::vector<std::int64_t>{20, 60, 140, 300, 620, 1260}));
  for (std::size_t i = 6; i < at.size(); ++i) {
    EXPECT_EQ(at[i] - at[i - 1], 640);
  }
}

TEST(LockstepRound, AStepsSamplesRestartTheIntervalAndANewRoundTheBackOff)
{
  LockstepRound round(kPeriod, kReportEvery);
  round.open(kPeriod, 0);
  round.published(0);
  EXPECT_EQ(resends(round, 60), (std::vector<std::int64_t>{20, 60}));
  round.published(70 * kMs);  // a step sent the samples: the next repeat is timed from then
  EXPECT_FALSE(round.resendDue(100 * kMs));
  EXPECT_TRUE(round.resendDue(150 * kMs));  // 80 ms on: the back-off holds within the round
  round.close();
  round.open(2 * kPeriod, 200 * kMs);
  round.published(200 * kMs);
  EXPECT_FALSE(round.resendDue(219 * kMs));
  EXPECT_TRUE(round.resendDue(220 * kMs));  // a new round starts again at 20 ms
}

TEST(LockstepRound, AWaitIsReportedOnceAPeriodFromItsStartAndNotBefore)
{
  LockstepRound round(kPeriod, 2'000 * kMs);
  round.open(0, 1'000 * kMs);
  EXPECT_FALSE(round.reportDue(2'999 * kMs));
  EXPECT_TRUE(round.reportDue(3'000 * kMs));
  EXPECT_EQ(round.waitedNs(3'000 * kMs), 2'000 * kMs);
  EXPECT_FALSE(round.reportDue(4'000 * kMs));
  EXPECT_TRUE(round.reportDue(5'000 * kMs));
  EXPECT_THROW(LockstepRound(0, kReportEvery), std::invalid_argument);
  EXPECT_THROW(LockstepRound(kPeriod, 0), std::invalid_argument);
}

}  // namespace
}  // namespace quad::runtime
