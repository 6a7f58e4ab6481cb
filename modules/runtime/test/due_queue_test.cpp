// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/due_queue.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace quad::runtime {
namespace {

std::vector<int> releaseAll(DueQueue<int>& queue, std::int64_t now_ns)
{
  std::vector<int> out;
  queue.release(now_ns, [&](const int& item) { out.push_back(item); });
  return out;
}

TEST(DueQueue, ReleasesWhatIsDueAtOrBeforeTheTimeHandledOnceInTheOrderHeld)
{
  DueQueue<int> queue;
  queue.hold(10, 1);
  queue.hold(10, 2);
  queue.hold(20, 3);
  EXPECT_EQ(queue.nextDueNs(), 10);
  EXPECT_TRUE(releaseAll(queue, 9).empty());
  EXPECT_EQ(releaseAll(queue, 10), (std::vector<int>{1, 2}));
  EXPECT_TRUE(releaseAll(queue, 10).empty());
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(releaseAll(queue, 1'000), (std::vector<int>{3}));
  EXPECT_TRUE(queue.empty());
  EXPECT_EQ(queue.nextDueNs(), std::nullopt);
}

TEST(DueQueue, AnItemWaitsBehindOneHeldBeforeItEvenOneDueLater)
{
  DueQueue<int> queue;
  queue.hold(50, 1);
  queue.hold(5, 2);  // due earlier, held later: the topic's order is kept
  EXPECT_TRUE(releaseAll(queue, 10).empty());
  EXPECT_EQ(releaseAll(queue, 50), (std::vector<int>{1, 2}));
}

TEST(DueQueue, OneAtATimeReleasesTheOldestOnlyWhenItIsDue)
{
  DueQueue<int> queue;
  queue.hold(10, 1);
  queue.hold(10, 2);
  queue.hold(30, 3);
  EXPECT_EQ(queue.releaseOne(9), std::nullopt);
  EXPECT_EQ(queue.releaseOne(10), 1);
  EXPECT_EQ(queue.releaseOne(10), 2);
  EXPECT_EQ(queue.releaseOne(20), std::nullopt);
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(queue.releaseOne(30), 3);
  EXPECT_EQ(queue.releaseOne(1'000), std::nullopt);
  EXPECT_TRUE(queue.empty());
}

TEST(DueQueue, HeldRisingAnItemDueBeforeThoseHeldLastDropsThemAndTheRestKeepTheirOrder)
{
  DueQueue<int> queue;
  std::vector<int> dropped;
  const auto drop = [&](const int& item) { dropped.push_back(item); };
  queue.holdRising(10, 1, drop);
  queue.holdRising(40, 2, drop);
  queue.holdRising(50, 3, drop);
  queue.holdRising(30, 4, drop);  // 2 and 3 were damaged: due after the one sent after them
  queue.holdRising(30, 5, drop);  // due with the one before it: kept
  EXPECT_EQ(dropped, (std::vector<int>{3, 2}));
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(releaseAll(queue, 25), (std::vector<int>{1}));
  EXPECT_EQ(releaseAll(queue, 30), (std::vector<int>{4, 5}));
  EXPECT_TRUE(queue.empty());
}

TEST(DueQueue, AnInputStampedBeforeAStateIsDueWithItAndOneStampedWithItIsNot)
{
  DueQueue<std::string> queue;
  queue.hold(dueAfter(3'996'000), "imu of 3.996 ms");
  queue.hold(dueAfter(4'000'000), "imu of 4.000 ms");
  std::vector<std::string> out;
  queue.release(4'000'000, [&](const std::string& s) { out.push_back(s); });  // the state of 4 ms
  EXPECT_EQ(out, (std::vector<std::string>{"imu of 3.996 ms"}));
}

TEST(DueQueue, AgreesWithAFromScratchScanOnRandomHoldsAndReleases)
{
  // Property: after any sequence of holds and releases, the items released so far are the
  // longest prefix of the holds, in order, whose due times are at or before the time handled
  // when each was released (computed from scratch over the whole history).
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    DueQueue<int> queue;
    std::vector<std::int64_t> due;  // every hold's due time, in order
    std::vector<int> released;
    std::size_t expected_released = 0;
    for (int step = 0; step < 40; ++step) {
      if (rng() % 2 == 0) {
        due.push_back(static_cast<std::int64_t>(rng() % 100));
        queue.hold(due.back(), static_cast<int>(due.size() - 1));
      } else {
        const auto now = static_cast<std::int64_t>(rng() % 100);
        queue.release(now, [&](const int& item) { released.push_back(item); });
        while (expected_released < due.size() && due[expected_released] <= now) {
          ++expected_released;
        }
      }
      ASSERT_EQ(released.size(), expected_released);
      for (std::size_t k = 0; k < released.size(); ++k) {
        ASSERT_EQ(released[k], static_cast<int>(k));
      }
      ASSERT_EQ(queue.size(), due.size() - expected_released);
    }
  }
}

}  // namespace
}  // namespace quad::runtime
