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

}  // namespace
}  // namespace quad::runtime
