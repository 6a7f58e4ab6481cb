// SPDX-License-Identifier: BSD-3-Clause
// A raw reader says when the middleware received a sample, not when it was taken: a reader
// that takes in batches (the recorder) keeps each sample's own time.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "side_by_side.hpp"
#include "wait.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 96;  // this test's own

TEST(RawSubscriber, SaysWhenTheMiddlewareReceivedASampleNotWhenItWasTaken)
{
  // GIVEN a clock writer and a raw reader of it on another participant
  Participant plant(test::sideBySide("plant", kDomain));
  Participant recorder(test::sideBySide("recorder", kDomain));
  Publisher<msg::SimClock> clock(plant, topics::kSimClock);
  RawSubscriber reader(recorder, topics::kSimClock.info, nullptr);
  ASSERT_TRUE(test::waitFor([&] { return clock.matchedReaders() == 1; }));

  // WHEN a sample is written, and taken only 400 ms later
  const std::int64_t written_ns = common::wallTimeNs();
  msg::SimClock tick;
  tick.sim_ns(4'000'000);
  ASSERT_TRUE(clock.write(tick));
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const std::int64_t taken_ns = common::wallTimeNs();
  RawSample sample;
  std::uint64_t writer = 0;
  std::int64_t received_ns = 0;
  ASSERT_TRUE(reader.take(sample, writer, received_ns));

  // THEN its time of reception lies after the write and well before the take
  EXPECT_GE(received_ns, written_ns);
  EXPECT_LT(received_ns, taken_ns - 200'000'000);
  EXPECT_NE(writer, 0U);
  EXPECT_FALSE(sample.payload.empty());
}

}  // namespace
}  // namespace quad::dds
