// SPDX-License-Identifier: BSD-3-Clause
// Following the plant's clock between two real participants: sim time never goes back, the
// newest sample says lockstep, frames and state, and a state is vouched for only up to
// kStateAheadOfClockNs past the clock.
#include <gtest/gtest.h>

#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/sim_clock.hpp"
#include "quad/dds/topics.hpp"
#include "wait.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 229;  // this test's own

msg::SimClock tick(std::int64_t sim_ns, bool lockstep, std::uint64_t frames, bool state_sent)
{
  msg::SimClock c;
  c.header().stamp_ns(sim_ns);
  c.sim_ns(sim_ns);
  c.step_ns(4'000'000);
  c.real_time_factor(1.0);
  c.lockstep(lockstep);
  c.depth_frames(frames);
  c.state_sent(state_sent);
  return c;
}

TEST(SimClockFollower, TimeOnlyMovesForwardAndTheNewestSampleSaysTheRest)
{
  intraprocessDeliveryOff();  // two participants in one process (participant.hpp)
  const auto options = [](const char* name) {
    return ParticipantOptions{.name = name, .domain_id = kDomain, .transport = Transport::kUdp};
  };
  Participant plant(options("plant"));
  Participant reader(options("reader"));
  Publisher<msg::SimClock> clock(plant, topics::kSimClock);
  SimClockFollower follower(reader);
  ASSERT_TRUE(test::waitFor([&] { return clock.matchedReaders() == 1; }));

  // GIVEN no clock yet: nothing seen, time 0
  EXPECT_FALSE(follower.update());
  EXPECT_FALSE(follower.seen());
  EXPECT_EQ(follower.ns(), 0);

  // WHEN the clock tells 2 s, then (late) 1 s
  ASSERT_TRUE(clock.write(tick(2'000'000'000, true, 20, true)));
  ASSERT_TRUE(test::waitFor([&] { return follower.update(); }));
  ASSERT_TRUE(clock.write(tick(1'000'000'000, false, 10, false)));
  ASSERT_TRUE(test::waitFor([&] { return follower.update(); }));

  // THEN time stays at the newest, and the newest sample's flags hold
  EXPECT_TRUE(follower.seen());
  EXPECT_EQ(follower.ns(), 2'000'000'000);
  EXPECT_EQ(follower.depthFrames(), 20U);
  EXPECT_FALSE(follower.lockstep());
  EXPECT_FALSE(follower.stateSent());
  // AND a state is vouched for up to half a second past the clock, not beyond
  EXPECT_TRUE(follower.vouchesFor(2'000'000'000));
  EXPECT_TRUE(follower.vouchesFor(2'000'000'000 + topics::kStateAheadOfClockNs));
  EXPECT_FALSE(follower.vouchesFor(2'000'000'001 + topics::kStateAheadOfClockNs));
}

}  // namespace
}  // namespace quad::dds
