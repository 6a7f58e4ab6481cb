// SPDX-License-Identifier: BSD-3-Clause
// A raw reader says when the middleware received a sample, not when it was taken: a reader
// that takes in batches (the recorder) keeps each sample's own time. Raw endpoints on a
// participant whose nodes use the topic typed (a container's, hosting the recorder) take and
// write through the typed support.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "side_by_side.hpp"
#include "wait.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 96;           // this test's own
constexpr int kContainerDomain = 207;  // and the container's

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

/// The clock sample a payload holds, decoded with `type`.
msg::SimClock decodeClock(const eprosima::fastdds::dds::TypeSupport& type, const RawSample& sample)
{
  TypedPayload typed(type);
  EXPECT_TRUE(typed.fromPayload(sample));
  return *static_cast<msg::SimClock*>(typed.data());
}

TEST(RawSubscriber, OnAParticipantWhoseNodesUseTheTopicTypedItTakesAndWritesThroughTheirTypeSupport)
{
  // GIVEN a container's participant whose nodes write the clock and read the lockstep reports
  // typed, and a raw reader of the clock on a participant of its own
  Participant container(test::sideBySide("container", kContainerDomain));
  Participant tool(test::sideBySide("tool", kContainerDomain));
  Publisher<msg::SimClock> clock(container, topics::kSimClock);
  Subscriber<msg::LockstepReport> reports(container, topics::kLockstep, nullptr);

  // WHEN a raw reader of the clock and a raw writer of the reports join the container's
  // participant (a type name has one serialisation per participant: theirs is the typed one)
  RawSubscriber hosted(container, topics::kSimClock.info, nullptr);
  RawPublisher report_writer(container, topics::kLockstep.info);
  RawSubscriber apart(tool, topics::kSimClock.info, nullptr);
  ASSERT_TRUE(test::waitFor([&] { return clock.matchedReaders() == 2 && reports.matchedWriters() == 1; }));
  msg::SimClock tick;
  tick.sim_ns(8'000'000);
  tick.lockstep(true);
  tick.depth_frames(3);
  tick.state_sent(false);
  ASSERT_TRUE(clock.write(tick));

  // THEN the hosted reader takes the payload the writer sent, as the reader apart does: each
  // decodes to the sample written
  const auto type = payloadTypeFor(container, topics::kSimClock.info);
  for (RawSubscriber* reader : {&hosted, &apart}) {
    RawSample sample;
    ASSERT_TRUE(test::waitFor([&] { return reader->take(sample); }));
    const msg::SimClock got = decodeClock(type, sample);
    EXPECT_EQ(got.sim_ns(), 8'000'000);
    EXPECT_TRUE(got.lockstep());
    EXPECT_EQ(got.depth_frames(), 3U);
    EXPECT_FALSE(got.state_sent());
  }

  // AND a report written raw there reaches the typed reader beside it as it was written
  msg::LockstepReport report;
  report.header().stamp_ns(8'000'000);
  report.participant("record");
  report.done_ns(12'000'000);
  TypedPayload encoder(payloadTypeFor(container, topics::kLockstep.info));
  *static_cast<msg::LockstepReport*>(encoder.data()) = report;
  RawSample raw;
  ASSERT_TRUE(encoder.toPayload(raw));
  ASSERT_TRUE(report_writer.write(raw));
  std::optional<msg::LockstepReport> heard;
  ASSERT_TRUE(test::waitFor([&] { return (heard = reports.take()).has_value(); }));
  EXPECT_EQ(heard->participant().to_string(), "record");
  EXPECT_EQ(heard->done_ns(), 12'000'000);
  EXPECT_EQ(heard->header().stamp_ns(), 8'000'000);
}

}  // namespace
}  // namespace quad::dds
