// SPDX-License-Identifier: BSD-3-Clause
// Several vehicles may share a domain: a node takes only its own vehicle's samples.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 157;  // this test's own

Participant vehicle(std::uint32_t id)
{
  return Participant(ParticipantOptions{.name = "vehicles_test_" + std::to_string(id), .domain_id = kDomain,
                                        .transport = Transport::kUdp, .vehicle_id = id});
}

TEST(Vehicles, ASubscriberTakesItsOwnVehicleOnlyAndCountsTheRest)
{
  Participant own = vehicle(0);
  Participant other = vehicle(7);
  Subscriber<msg::Goal> reader(own, topics::kGoal);
  Publisher<msg::Goal> mine(own, topics::kGoal);
  Publisher<msg::Goal> theirs(other, topics::kGoal);
  const std::int64_t deadline = common::steadyTimeNs() + 5 * common::kNanosecondsPerSecond;
  while ((reader.matchedWriters() < 2 || theirs.matchedReaders() < 1) && common::steadyTimeNs() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(reader.matchedWriters(), 2);
  msg::Goal g;
  g.goal_id(70);
  ASSERT_TRUE(theirs.write(g));
  g.goal_id(1);
  ASSERT_TRUE(mine.write(g));
  std::vector<msg::Goal> got;
  while (got.empty() && common::steadyTimeNs() < deadline) {
    got = reader.takeAll();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Both were sent before either was taken: the latched goal of vehicle 7 arrived too.
  while (reader.foreignSamples() == 0 && common::steadyTimeNs() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (const auto& s : reader.takeAll()) {
      got.push_back(s);
    }
  }
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].goal_id(), 1U);
  EXPECT_EQ(got[0].header().vehicle_id(), 0U);
  EXPECT_EQ(reader.foreignSamples(), 1U);
}

}  // namespace
}  // namespace quad::dds
