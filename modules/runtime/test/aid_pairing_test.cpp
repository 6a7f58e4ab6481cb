// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/aid_pairing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace quad::runtime {
namespace {

// Triggers are numbered samples; an aid is named by its kind and number ("p3": position 3).
using Pairing = AidPairing<int, std::string, 2>;
constexpr std::int64_t kGraceNs = 200;

std::string aid(std::size_t kind, std::uint64_t seq) { return (kind == 0 ? "p" : "b") + std::to_string(seq); }

void hold(Pairing& pairing, std::size_t kind, std::uint64_t seq) { pairing.holdAid(kind, seq, aid(kind, seq)); }

TEST(AidPairing, ATriggerWaitsForTheAidsItNamesAndComesWithThoseOnly)
{
  Pairing pairing(kGraceNs);
  pairing.holdTrigger(1, {0, 0});  // the first: nothing written before it
  ASSERT_TRUE(pairing.next(10, true).has_value());
  pairing.holdTrigger(2, {2, 1});
  hold(pairing, 0, 1);
  hold(pairing, 0, 2);
  EXPECT_FALSE(pairing.next(20, true).has_value()) << "b1 has not come";
  hold(pairing, 0, 3);  // written after trigger 2: due with a later one
  hold(pairing, 1, 1);
  const auto paired = pairing.next(30, true);
  ASSERT_TRUE(paired.has_value());
  EXPECT_EQ(paired->trigger, 2);
  EXPECT_EQ(paired->aids, (std::vector<std::string>{"p1", "p2", "b1"}));
  EXPECT_FALSE(paired->lost);
  pairing.holdTrigger(3, {3, 1});
  const auto next = pairing.next(40, true);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->aids, (std::vector<std::string>{"p3"}));
  EXPECT_EQ(pairing.front(), nullptr);
}

TEST(AidPairing, TheFirstWaitsForTheWritersAndWhatItNamesIsLeftOut)
{
  Pairing pairing(kGraceNs);
  hold(pairing, 0, 4);  // came before this reader matched every writer: partial history
  pairing.holdTrigger(1, {5, 2});
  EXPECT_FALSE(pairing.next(10, false).has_value());
  EXPECT_FALSE(pairing.answeredAny());
  hold(pairing, 0, 5);
  const auto first = pairing.next(20, true);
  ASSERT_TRUE(first.has_value());
  EXPECT_TRUE(first->aids.empty());
  EXPECT_EQ(first->left_out, 2u);
  EXPECT_TRUE(pairing.answeredAny());
  pairing.holdTrigger(2, {6, 2});
  hold(pairing, 0, 6);
  const auto second = pairing.next(30, false);  // the writers matter before the first only
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->aids, (std::vector<std::string>{"p6"}));
}

TEST(AidPairing, AnAidThatDoesNotComeIsWaitedForTheGraceThenLeftOut)
{
  Pairing pairing(kGraceNs);
  pairing.holdTrigger(1, {0, 0});
  ASSERT_TRUE(pairing.next(0, true).has_value());
  pairing.holdTrigger(2, {1, 1});
  hold(pairing, 1, 1);  // p1 is lost on the way
  EXPECT_FALSE(pairing.next(1'000, true).has_value());
  EXPECT_FALSE(pairing.next(1'000 + kGraceNs - 1, true).has_value());
  const auto paired = pairing.next(1'000 + kGraceNs, true);
  ASSERT_TRUE(paired.has_value());
  EXPECT_TRUE(paired->lost);
  EXPECT_EQ(paired->aids, (std::vector<std::string>{"b1"}));
  EXPECT_EQ(paired->wanted, (Pairing::Numbers{1, 1}));
  EXPECT_EQ(paired->newest, (Pairing::Numbers{0, 1}));
  // The next one waits a grace of its own.
  pairing.holdTrigger(3, {2, 1});
  EXPECT_FALSE(pairing.next(5'000, true).has_value());
  EXPECT_FALSE(pairing.next(5'000 + kGraceNs - 1, true).has_value());
  hold(pairing, 0, 2);
  EXPECT_EQ(pairing.next(5'000 + kGraceNs - 1, true)->aids, (std::vector<std::string>{"p2"}));
}

TEST(AidPairing, ATriggerDroppedIsNeverHandedOut)
{
  Pairing pairing(kGraceNs);
  pairing.holdTrigger(1, {0, 0});
  pairing.holdTrigger(1, {0, 0});  // sent again
  ASSERT_EQ(pairing.next(0, true)->trigger, 1);
  ASSERT_NE(pairing.front(), nullptr);
  pairing.dropFront();
  EXPECT_EQ(pairing.front(), nullptr);
  EXPECT_FALSE(pairing.next(1, true).has_value());
}

TEST(AidPairing, InAnyOrderOfArrivalEachTriggerComesWithTheAidsWrittenBetweenItAndTheOneBefore)
{
  // Property: a writer's history (aids and triggers interleaved, each trigger naming the
  // newest aid of each kind before it) delivered in a random order that keeps each topic's
  // own order pairs every trigger with exactly the aids written since the trigger before it.
  for (unsigned seed = 1; seed <= 50; ++seed) {
    std::mt19937 rng(seed);
    struct Event {
      bool trigger;
      std::size_t kind;
      std::uint64_t seq;
      Pairing::Numbers wanted;
    };
    std::vector<Event> history{{true, 0, 0, {0, 0}}};  // the first names nothing
    Pairing::Numbers written{};
    std::vector<std::vector<std::string>> expected{{}};  // trigger k's aids
    std::vector<std::string> since;                      // written since the last trigger
    for (int i = 0; i < 60; ++i) {
      if (rng() % 3 == 0) {
        history.push_back({true, 0, static_cast<std::uint64_t>(expected.size()), written});
        expected.push_back(since);
        since.clear();
      } else {
        const std::size_t kind = rng() % 2;
        ++written[kind];
        history.push_back({false, kind, written[kind], {}});
        since.push_back(aid(kind, written[kind]));  // due with the next trigger, if one comes
      }
    }
    // Deliver: three streams (triggers, kind 0, kind 1), each in order, merged at random.
    std::vector<std::vector<Event>> streams(3);
    for (const Event& e : history) {
      streams[e.trigger ? 0 : 1 + e.kind].push_back(e);
    }
    std::vector<std::size_t> at(3, 0);
    Pairing pairing(kGraceNs);
    std::vector<std::vector<std::string>> got;
    while (at[0] < streams[0].size() || at[1] < streams[1].size() || at[2] < streams[2].size()) {
      std::size_t s = rng() % 3;
      while (at[s] == streams[s].size()) {
        s = (s + 1) % 3;
      }
      const Event& e = streams[s][at[s]++];
      if (e.trigger) {
        pairing.holdTrigger(static_cast<int>(e.seq), e.wanted);
      } else {
        hold(pairing, e.kind, e.seq);
      }
      while (auto p = pairing.next(0, true)) {
        ASSERT_FALSE(p->lost) << seed;
        ASSERT_EQ(p->trigger, static_cast<int>(got.size())) << seed;
        std::vector<std::string> aids = p->aids;
        std::vector<std::string> want = expected[got.size()];
        std::sort(aids.begin(), aids.end());
        std::sort(want.begin(), want.end());
        ASSERT_EQ(aids, want) << "seed " << seed << ", trigger " << got.size();
        got.push_back(p->aids);
      }
    }
    EXPECT_EQ(got.size(), expected.size()) << seed;
  }
}

}  // namespace
}  // namespace quad::runtime
