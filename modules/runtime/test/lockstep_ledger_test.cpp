// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/lockstep_ledger.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::runtime {
namespace {

TEST(LockstepLedger, CaughtUpOnlyWhenEveryParticipantReachedTheTime)
{
  LockstepLedger ledger({"control", "mapping"});
  EXPECT_FALSE(ledger.caughtUp(0));
  EXPECT_EQ(ledger.report("control", 2'000'000), LockstepLedger::Report::kAccepted);
  EXPECT_FALSE(ledger.caughtUp(1'000'000));
  EXPECT_EQ(ledger.report("mapping", 1'000'000), LockstepLedger::Report::kAccepted);
  EXPECT_TRUE(ledger.caughtUp(1'000'000));
  EXPECT_FALSE(ledger.caughtUp(1'000'001));
  EXPECT_EQ(ledger.minimumDoneNs(), 1'000'000);
}

TEST(LockstepLedger, LateListNamesWhoAndHowFar)
{
  LockstepLedger ledger({"control", "mapping", "planning"});
  ledger.report("mapping", 1'200'000'000);
  ledger.report("planning", 2'000'000'000);
  EXPECT_EQ(ledger.late(1'204'000'000),
            (std::vector<std::string>{"control (no report yet)", "mapping (done up to 1.200 s)"}));
  EXPECT_EQ(ledger.lateNames(1'204'000'000), (std::vector<std::string>{"control", "mapping"}));
  EXPECT_TRUE(ledger.lateNames(1'200'000'000) == std::vector<std::string>{"control"});
}

TEST(LockstepLedger, UnknownAndBackwardReportsAreIgnored)
{
  LockstepLedger ledger({"control"});
  EXPECT_EQ(ledger.report("intruder", 5), LockstepLedger::Report::kUnknownParticipant);
  EXPECT_EQ(ledger.report("control", 10), LockstepLedger::Report::kAccepted);
  EXPECT_EQ(ledger.report("control", 9), LockstepLedger::Report::kWentBackwards);
  EXPECT_EQ(ledger.doneNs("control"), 10);
  EXPECT_EQ(ledger.report("control", 10), LockstepLedger::Report::kAccepted);  // repeat is fine
}

TEST(LockstepLedger, NamesMustBeUniqueAndNonEmpty)
{
  EXPECT_THROW(LockstepLedger({"a", "a"}), std::invalid_argument);
  EXPECT_THROW(LockstepLedger({""}), std::invalid_argument);
}

TEST(LockstepLedger, CaughtUpEqualsTheMinimumOfRandomReports)
{
  // Property: for any report sequence, caughtUp(t) <=> t <= min over participants of their
  // largest accepted report.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    LockstepLedger ledger({"a", "b", "c"});
    std::int64_t best[3] = {-1, -1, -1};
    for (int k = 0; k < 20; ++k) {
      const int who = static_cast<int>(rng() % 3);
      const std::int64_t t = static_cast<std::int64_t>(rng() % 1000);
      if (ledger.report(std::string(1, static_cast<char>('a' + who)), t) ==
          LockstepLedger::Report::kAccepted) {
        best[who] = t;
      }
    }
    const std::int64_t minimum = std::min({best[0], best[1], best[2]});
    for (std::int64_t t = 0; t < 1000; t += 37) {
      EXPECT_EQ(ledger.caughtUp(t), minimum >= 0 && t <= minimum) << "t=" << t;
    }
  }
}

TEST(LockstepLedger, AParticipantOnInputsOnlyHoldsTheClockOnlyAtAnInputsDueTimeUntilItIsDone)
{
  LockstepLedger ledger({"mapping", "planning"});
  ASSERT_TRUE(ledger.worksOnInputsOnly("mapping"));
  EXPECT_FALSE(ledger.worksOnInputsOnly("intruder"));
  ledger.report("planning", 10'000'000'000);
  // Before its first report it is late like any other.
  EXPECT_FALSE(ledger.caughtUp(0));
  EXPECT_EQ(ledger.late(0), (std::vector<std::string>{"mapping (no report yet)"}));
  // Done with nothing given: nothing holds the clock, however far it runs.
  ledger.report("mapping", 54'000'000);
  EXPECT_TRUE(ledger.caughtUp(9'000'000'000));
  // A frame at 0.1 s due at 0.15 s: the clock runs up to just before, and stands there.
  ledger.inputGiven("mapping", 150'000'000);
  EXPECT_TRUE(ledger.caughtUp(149'999'999));
  EXPECT_FALSE(ledger.caughtUp(150'000'000));
  EXPECT_EQ(ledger.doneUpToNs("mapping"), 149'999'999);
  EXPECT_EQ(ledger.doneNs("mapping"), 54'000'000);  // what it reported
  // A second frame given before the first is done: still held at the first's due time.
  ledger.inputGiven("mapping", 250'000'000);
  EXPECT_FALSE(ledger.caughtUp(150'000'000));
  // The first done: held at the second's.
  ledger.report("mapping", 150'000'000);
  EXPECT_TRUE(ledger.caughtUp(249'999'999));
  EXPECT_FALSE(ledger.caughtUp(250'000'000));
  EXPECT_EQ(ledger.lateNames(250'000'000), (std::vector<std::string>{"mapping"}));
  // Both done: free again; an input due no later than its report adds no wait.
  ledger.report("mapping", 260'000'000);
  EXPECT_TRUE(ledger.caughtUp(9'000'000'000));
  ledger.inputGiven("mapping", 255'000'000);
  EXPECT_TRUE(ledger.caughtUp(9'000'000'000));
  EXPECT_EQ(ledger.minimumDoneNs(), 10'000'000'000);  // the planner's report
  // An input given to a participant not on inputs only changes nothing.
  EXPECT_TRUE(ledger.inputGiven("planning", 20'000'000'000));
  EXPECT_TRUE(ledger.caughtUp(10'000'000'000));
  EXPECT_FALSE(ledger.caughtUp(10'000'000'001));
  EXPECT_FALSE(ledger.inputGiven("intruder", 1));
}

TEST(LockstepLedger, OnInputsOnlyCaughtUpMeansEveryInputDueByThenWasReportedDone)
{
  // Property: for random inputs and reports, caughtUp(t) <=> the participant reported, and
  // reported done up to t, or up to the due time of every input given that is due by t.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    LockstepLedger ledger({"m"});
    ledger.worksOnInputsOnly("m");
    std::vector<std::int64_t> dues;
    std::int64_t reported = -1;
    std::int64_t next_due = 0;
    for (int k = 0; k < 30; ++k) {
      if (rng() % 2 == 0) {
        next_due += static_cast<std::int64_t>(rng() % 50);
        dues.push_back(next_due);
        ledger.inputGiven("m", next_due);
      } else {
        const std::int64_t t = static_cast<std::int64_t>(rng() % 1500);
        if (ledger.report("m", t) == LockstepLedger::Report::kAccepted) {
          reported = t;
        }
      }
      for (std::int64_t t = 0; t < 1600; t += 23) {
        bool expected = reported >= 0;
        if (expected && reported < t) {
          for (const std::int64_t due : dues) {
            expected = expected && (due > t || due <= reported);
          }
        }
        ASSERT_EQ(ledger.caughtUp(t), expected) << "trial " << trial << ", t=" << t;
      }
    }
  }
}

}  // namespace
}  // namespace quad::runtime
