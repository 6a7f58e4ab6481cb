// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/state_timed.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

namespace quad::runtime {
namespace {

constexpr std::int64_t kWaitNs = 500;

/// What a reader's release hands out, with the pose known up to `pose_known_until` and no
/// state sent at the times in `unsent`.
std::vector<int> releaseAll(StateTimed<int>& held, const StateProgress& progress, std::int64_t pose_known_until = -1,
                            const std::set<std::int64_t>& unsent = {})
{
  std::vector<int> out;
  held.release(
      progress, [&](std::int64_t stamp) { return stamp <= pose_known_until; },
      [&](std::int64_t stamp) { return !unsent.contains(stamp); }, [&](const int& item) { out.push_back(item); });
  return out;
}

TEST(StateTimed, InLockstepAnInputWaitsForTheStateOfItsOwnTimeThenGoesInTheOrderHeld)
{
  StateTimed<int> held(kWaitNs);
  held.hold(100, 1);
  held.hold(200, 2);
  EXPECT_EQ(held.oldestStampNs(), 100);
  EXPECT_EQ(held.newest(), 2);
  // The clock past both, a pose known for both (carried on from an older state): not enough.
  EXPECT_TRUE(releaseAll(held, {true, 99, 10'000}, 10'000).empty());
  EXPECT_EQ(releaseAll(held, {true, 100, 10'000}), (std::vector<int>{1}));
  EXPECT_EQ(held.size(), 1u);
  EXPECT_EQ(releaseAll(held, {true, 250, 250}), (std::vector<int>{2}));
  EXPECT_TRUE(held.empty());
}

TEST(StateTimed, InLockstepAnInputGoesWithoutItsStateOnlyOnceTheClockOfItsTimeSaidNoneWasSent)
{
  StateTimed<int> held(kWaitNs);
  held.hold(100, 1);
  held.hold(200, 2);
  // No state of 100 sent, but the clock not there yet: it still waits.
  EXPECT_TRUE(releaseAll(held, {true, 96, 96}, -1, {100}).empty());
  // The clock there: the first goes; the second, whose state was sent, waits for it, however
  // far the clock runs on.
  EXPECT_EQ(releaseAll(held, {true, 96, 100}, -1, {100}), (std::vector<int>{1}));
  EXPECT_TRUE(releaseAll(held, {true, 196, 5'000}, -1, {100}).empty());
  EXPECT_EQ(releaseAll(held, {true, 200, 5'000}, -1, {100}), (std::vector<int>{2}));
}

TEST(StateTimed, InRealTimeAnInputGoesOnceItsPoseIsKnownOrAfterWaitingTheLimit)
{
  StateTimed<int> held(kWaitNs);
  held.hold(100, 1);
  held.hold(200, 2);
  held.hold(300, 3);
  EXPECT_TRUE(releaseAll(held, {false, 50, 100 + kWaitNs}).empty());
  EXPECT_EQ(releaseAll(held, {false, 50, 100 + kWaitNs}, 100), (std::vector<int>{1}));
  // Past the limit with no pose: it goes (the reader refuses it, naming the missing state).
  EXPECT_EQ(releaseAll(held, {false, 50, 200 + kWaitNs + 1}), (std::vector<int>{2}));
  // A state of its time or later came without a pose for it (a gap): it goes too.
  EXPECT_EQ(releaseAll(held, {false, 300, 300}), (std::vector<int>{3}));
}

TEST(StateTimed, KeepingTheNewestDropsEveryOtherInput)
{
  StateTimed<int> held(kWaitNs);
  EXPECT_EQ(held.keepNewest(), 0u);
  held.hold(100, 1);
  EXPECT_EQ(held.keepNewest(), 0u);
  held.hold(200, 2);
  held.hold(300, 3);
  EXPECT_EQ(held.keepNewest(), 2u);
  EXPECT_EQ(held.size(), 1u);
  EXPECT_EQ(held.newest(), 3);
  EXPECT_EQ(held.oldestStampNs(), 300);
}

TEST(StateTimed, InLockstepNothingGoesBeforeItsStateOrTheClockSayingNoneWasSentAndNothingIsReordered)
{
  // 50 random lockstep histories: inputs every few steps, states every step but some dropped,
  // the reader releasing at random moments as the clock and the states it heard advance.
  std::mt19937 rng(7);
  for (int history = 0; history < 50; ++history) {
    StateTimed<int> held(kWaitNs);
    std::set<std::int64_t> unsent;
    std::vector<int> released;
    std::int64_t heard = -1;
    std::int64_t clock = 0;
    int next = 0;
    std::vector<std::int64_t> stamps;
    for (std::int64_t t = 0; t < 2'000; t += 4) {
      clock = t;
      if (std::uniform_int_distribution<int>(0, 9)(rng) == 0) {
        unsent.insert(t);  // this step's state dropped
      } else if (std::uniform_int_distribution<int>(0, 2)(rng) != 0) {
        heard = t;  // heard now; a state heard late is heard with a later one
      }
      if (t % 20 == 0) {
        held.hold(t, next++);
        stamps.push_back(t);
      }
      if (std::uniform_int_distribution<int>(0, 3)(rng) == 0) {
        held.release(
            {true, heard, clock}, [](std::int64_t) { return true; },
            [&](std::int64_t s) { return !unsent.contains(s); },
            [&](const int& item) {
              const std::int64_t stamp = stamps[static_cast<std::size_t>(item)];
              EXPECT_TRUE(heard >= stamp || (clock >= stamp && unsent.contains(stamp)))
                  << "history " << history << ": input stamped " << stamp << " went with states heard to " << heard;
              released.push_back(item);
            });
      }
    }
    // Released in the order held, and what is still held is the rest, in order.
    for (std::size_t i = 0; i < released.size(); ++i) {
      ASSERT_EQ(released[i], static_cast<int>(i)) << "history " << history;
    }
    EXPECT_EQ(released.size() + held.size(), stamps.size());
  }
}

}  // namespace
}  // namespace quad::runtime
