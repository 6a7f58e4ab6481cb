// SPDX-License-Identifier: BSD-3-Clause
// The clock owner's round: the sim time it spans, and while it waits, when its samples go out
// again and when the wait is reported.
#include "quad/runtime/lockstep_round.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
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

TEST(LockstepRound, AWaitCountsToEachParticipantLateWhileItLastedAndTheRoundOnceToEach)
{
  LockstepRound round(kPeriod, kReportEvery);
  round.open(0, 0);
  round.waitingFor(1 * kMs, {"control", "mapping", "control"});  // both late since the round opened
  round.waitingFor(3 * kMs, {"mapping"});             // the command came at 3 ms
  round.waitingFor(10 * kMs, {"mapping"});
  EXPECT_TRUE(round.waiting());
  round.inputsIn(12 * kMs);
  EXPECT_FALSE(round.waiting());
  round.close();
  round.open(kPeriod, 20 * kMs);
  round.inputsIn(21 * kMs);  // no wait: nothing counts
  round.close();
  round.open(2 * kPeriod, 30 * kMs);
  round.waitingFor(30 * kMs, {"planning"});
  round.inputsIn(35 * kMs);

  EXPECT_EQ(round.roundsWaited(), 2u);
  EXPECT_EQ(round.waitedWallNs(), 17 * kMs);
  ASSERT_EQ(round.waits().size(), 3u);
  EXPECT_EQ(round.waits().at("control").wall_ns, 3 * kMs);
  EXPECT_EQ(round.waits().at("control").rounds, 1u);
  EXPECT_EQ(round.waits().at("mapping").wall_ns, 12 * kMs);
  EXPECT_EQ(round.waits().at("mapping").rounds, 1u);
  EXPECT_EQ(round.waits().at("planning").wall_ns, 5 * kMs);
}

TEST(LockstepRound, AWaitCheckedWheneverAnInputComesCountsEachParticipantExactlyTheTimeItWasLate)
{
  // 300 rounds of three participants, each done at a random wall time into its round (or
  // before it opened); the clock owner checks when the round opens and whenever one is done,
  // as the plant does. Each is counted exactly the time from the round's opening to its being
  // done, in the rounds where that is after the opening.
  const std::vector<std::string> names{"control", "mapping", "planning"};
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> done_at(-2 * kMs, 6 * kMs);
  LockstepRound round(kPeriod, kReportEvery);
  std::map<std::string, LockstepRound::Wait> expected;
  std::uint64_t rounds_waited = 0;
  std::int64_t waited = 0;
  std::int64_t now = 0;
  for (int r = 0; r < 300; ++r) {
    round.open(r * kPeriod, now);
    std::map<std::string, std::int64_t> done;
    for (const auto& n : names) {
      done[n] = now + done_at(rng);
    }
    const auto lateAt = [&](std::int64_t t) {
      std::vector<std::string> late;
      for (const auto& n : names) {
        if (done[n] > t) {
          late.push_back(n);
        }
      }
      return late;
    };
    std::vector<std::int64_t> checks{now};
    for (const auto& [n, t] : done) {
      if (t > now) {
        checks.push_back(t);
      }
    }
    std::sort(checks.begin(), checks.end());
    for (const std::int64_t t : checks) {
      if (const auto late = lateAt(t); !late.empty()) {
        round.waitingFor(t, late);
      } else {
        round.inputsIn(t);
      }
    }
    const std::int64_t end = checks.back();
    if (end > now) {
      ++rounds_waited;
      waited += end - now;
      for (const auto& [n, t] : done) {
        if (t > now) {
          expected[n].wall_ns += t - now;
          ++expected[n].rounds;
        }
      }
    }
    round.close();
    now = end + kMs;
  }
  EXPECT_EQ(round.roundsWaited(), rounds_waited);
  EXPECT_EQ(round.waitedWallNs(), waited);
  for (const auto& n : names) {
    ASSERT_EQ(round.waits().count(n), 1u) << n;
    EXPECT_EQ(round.waits().at(n).wall_ns, expected[n].wall_ns) << n;
    EXPECT_EQ(round.waits().at(n).rounds, expected[n].rounds) << n;
  }
}

}  // namespace
}  // namespace quad::runtime
