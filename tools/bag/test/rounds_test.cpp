// SPDX-License-Identifier: BSD-3-Clause
// A lockstep recording cut into its clock's rounds: each input lands before the first clock
// at or past its stamp, a resent sample once, and the clock's resends make no new round.
#include "quad/bag/rounds.hpp"

#include <gtest/gtest.h>

#include "quad/introspection/cdr.hpp"

namespace quad::bag {
namespace {

namespace in = quad::introspection;
using Json = nlohmann::ordered_json;

Json header(std::int64_t t_ns, std::uint64_t seq) { return {{"stamp_ns", t_ns}, {"publish_ns", 1000 + seq}, {"seq", seq}}; }

std::vector<std::uint8_t> clock(std::int64_t t_ns, std::uint64_t seq, bool state_sent)
{
  return in::encodeCdr(in::quadSchema(), "quad::msg::SimClock",
                       {{"header", header(t_ns, seq)}, {"sim_ns", t_ns}, {"lockstep", true}, {"state_sent", state_sent}});
}

std::vector<std::uint8_t> goal(std::int64_t t_ns, std::uint64_t seq, std::uint32_t id)
{
  return in::encodeCdr(in::quadSchema(), "quad::msg::Goal", {{"header", header(t_ns, seq)}, {"goal_id", id}});
}

TEST(Rounds, InputsLandBeforeTheFirstClockAtOrPastTheirStampAndResendsCountOnce)
{
  McapContents c;
  c.schemas = {{1, "quad::msg::SimClock", "omgidl", ""}, {2, "quad::msg::Goal", "omgidl", ""}};
  c.channels = {{1, 1, "quad/sim/clock", "cdr", {}}, {2, 2, "quad/planning/goal", "cdr", {}},
                {3, 2, "quad/not/an/input", "cdr", {}}};
  std::uint64_t log = 0;
  const auto add = [&](std::uint16_t channel, std::vector<std::uint8_t> data) {
    c.messages.push_back({channel, 0, ++log, 0, std::move(data)});
  };
  add(1, clock(0, 1, true));
  add(2, goal(5, 1, 7));        // recorded after clock 0, stamped between the rounds
  add(1, clock(10, 2, false));
  add(1, clock(10, 3, false));  // the plant resent it while waiting
  add(2, goal(5, 2, 7));        // resent: the same goal
  add(2, goal(10, 3, 8));
  add(3, goal(10, 1, 9));       // not an input
  add(1, clock(20, 4, true));
  add(2, goal(0, 4, 6));        // recorded late, stamped at the start
  add(2, goal(25, 5, 10));      // past the last clock
  const auto rounds = lockstepRounds(c, "quad/sim/clock", [](const std::string& t) { return t == "quad/planning/goal"; });
  ASSERT_EQ(rounds.size(), 3U);
  EXPECT_EQ(rounds[0].sim_ns, 0);
  EXPECT_TRUE(rounds[0].state_sent);
  EXPECT_FALSE(rounds[1].state_sent);
  EXPECT_EQ(rounds[2].sim_ns, 20);
  const auto ids = [](const Round& r) {
    std::vector<std::uint32_t> out;
    for (const Message* m : r.inputs) {
      out.push_back(in::decodeCdr(in::quadSchema(), "quad::msg::Goal", m->data)["goal_id"].get<std::uint32_t>());
    }
    return out;
  };
  EXPECT_EQ(ids(rounds[0]), (std::vector<std::uint32_t>{6}));
  EXPECT_EQ(ids(rounds[1]), (std::vector<std::uint32_t>{7, 8}));
  EXPECT_TRUE(rounds[2].inputs.empty());
}

TEST(Rounds, TheFirstLostInputIsPlacedAtTheJumpInItsNumbers)
{
  McapContents c;
  c.schemas = {{2, "quad::msg::Goal", "omgidl", ""}};
  c.channels = {{1, 2, "quad/planning/goal", "cdr", {}}, {2, 2, "quad/system/command", "cdr", {}},
                {3, 2, "quad/not/an/input", "cdr", {}}};
  std::uint64_t log = 0;
  const auto add = [&](std::uint16_t channel, std::int64_t t, std::uint64_t seq) {
    c.messages.push_back({channel, 0, ++log, 0, goal(t, seq, 1)});
  };
  add(1, 10, 1);
  add(1, 20, 2);
  add(1, 40, 4);  // 3 lost
  add(2, 5, 1);
  add(2, 30, 2);
  add(3, 1, 1);
  add(3, 9, 5);  // a jump too, but not an input
  const auto is_input = [](const std::string& t) { return t != "quad/not/an/input"; };
  // Without loss figures, nothing was lost.
  EXPECT_FALSE(firstLostInput(c, is_input));
  c.metadata.push_back({"quad.loss",
                        {{"quad/planning/goal", "received 3 missing 1 duplicated 0 reordered 0 writers 1"},
                         {"quad/system/command", "received 2 missing 0 duplicated 0 reordered 0 writers 1"},
                         {"quad/not/an/input", "received 2 missing 3 duplicated 0 reordered 0 writers 1"}}});
  auto lost = firstLostInput(c, is_input);
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->topic, "quad/planning/goal");
  EXPECT_EQ(lost->last_whole_ns, 20);
  // Two writers: the gap cannot be placed, so nothing after the first message is whole.
  c.metadata.back().values["quad/planning/goal"] = "received 3 missing 1 duplicated 0 reordered 0 writers 2";
  lost = firstLostInput(c, is_input);
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->last_whole_ns, 10);
}

TEST(Rounds, AClockThatIsNoSimClockIsAnError)
{
  McapContents c;
  c.schemas = {{1, "quad::msg::Goal", "omgidl", ""}};
  c.channels = {{1, 1, "quad/sim/clock", "cdr", {}}};
  c.messages.push_back({1, 0, 1, 0, {0, 1, 0, 0, 1}});
  EXPECT_THROW(lockstepRounds(c, "quad/sim/clock", [](const std::string&) { return true; }), BagError);
}

}  // namespace
}  // namespace quad::bag
