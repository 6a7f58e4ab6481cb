// SPDX-License-Identifier: BSD-3-Clause
// Following the plant's clock between two real participants: sim time never goes back, the
// newest sample says lockstep, frames and state, and a state is vouched for only up to
// kStateAheadOfClockNs past the clock; the depth frames published up to a time, and the times
// no state was sent, are kept from the samples taken.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/sim_clock.hpp"
#include "side_by_side.hpp"
#include "wait.hpp"

namespace quad::runtime {
namespace {

// Each test has a domain of its own: ctest runs them side by side, and one's clock samples
// must not reach the other's follower.
constexpr int kFollowingDomain = 229;
constexpr int kKeepingDomain = 95;

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

/// The plant's clock writer and a follower on another participant, on one domain.
struct ClockLink {
  explicit ClockLink(int domain)
      : plant{test::sideBySide("plant", domain)}, reader{test::sideBySide("reader", domain)}
  {
  }
  dds::Participant plant;
  dds::Participant reader;
  dds::Publisher<msg::SimClock> clock{plant, dds::topics::kSimClock};
  SimClockFollower follower{reader};
};

TEST(SimClockFollower, TimeOnlyMovesForwardAndTheNewestSampleSaysTheRest)
{
  ClockLink link{kFollowingDomain};
  auto& clock = link.clock;
  auto& follower = link.follower;
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
  EXPECT_TRUE(follower.vouchesFor(2'000'000'000 + dds::topics::kStateAheadOfClockNs));
  EXPECT_FALSE(follower.vouchesFor(2'000'000'001 + dds::topics::kStateAheadOfClockNs));
}

TEST(SimClockFollower, KeepsTheFramesPublishedAndTheStatesNotSentUpToATimeForTwoSeconds)
{
  ClockLink link{kKeepingDomain};
  auto& clock = link.clock;
  auto& follower = link.follower;
  ASSERT_TRUE(test::waitFor([&] { return clock.matchedReaders() == 1; }));

  // GIVEN clock samples at 0 (no frame yet), 0.1 s (the first), 0.104 s (no state sent: a
  // fault dropped it), 0.2 s (the second frame)
  for (const auto& [ns, frames, state_sent] : std::vector<std::tuple<std::int64_t, std::uint64_t, bool>>{
           {0, 0, true}, {100'000'000, 1, true}, {104'000'000, 1, false}, {200'000'000, 2, true}}) {
    ASSERT_TRUE(clock.write(tick(ns, true, frames, state_sent)));
    ASSERT_TRUE(test::waitFor([&] { return follower.update(); }));
  }
  // THEN the state of each sample's time was sent but for the one that said not
  EXPECT_TRUE(follower.stateSentAt(100'000'000));
  EXPECT_FALSE(follower.stateSentAt(104'000'000));
  EXPECT_TRUE(follower.stateSentAt(200'000'000));
  // AND a time counts the frames of the newest sample at or before it
  EXPECT_EQ(follower.depthFramesAt(-1), 0U);
  EXPECT_EQ(follower.depthFramesAt(99'999'999), 0U);
  EXPECT_EQ(follower.depthFramesAt(100'000'000), 1U);
  EXPECT_EQ(follower.depthFramesAt(199'999'999), 1U);
  EXPECT_EQ(follower.depthFramesAt(200'000'000), 2U);
  EXPECT_EQ(follower.depthFramesAt(5'000'000'000), 2U);

  // WHEN the clock reaches 3 s with 30 frames
  ASSERT_TRUE(clock.write(tick(3'000'000'000, true, 30, true)));
  ASSERT_TRUE(test::waitFor([&] { return follower.update(); }));
  // THEN the last two seconds still count as they did, and the newest sample from its time
  EXPECT_EQ(follower.depthFramesAt(1'000'000'000), 2U);
  EXPECT_EQ(follower.depthFramesAt(2'999'999'999), 2U);
  EXPECT_EQ(follower.depthFramesAt(3'000'000'000), 30U);
  // AND what lies further back is forgotten but for the count in force two seconds ago
  EXPECT_EQ(follower.depthFramesAt(150'000'000), 0U);
  EXPECT_TRUE(follower.stateSentAt(104'000'000));
}

}  // namespace
}  // namespace quad::runtime
