// SPDX-License-Identifier: BSD-3-Clause
// A reader's minimum separation in sim time between real participants: it takes one sample a
// period, and the writer does not send it the others.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/sim_period_filter.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "side_by_side.hpp"
#include "wait.hpp"

namespace quad::dds {
namespace {

constexpr int kDomain = 113;  // this test's own

/// A participant whose received datagrams are counted (its fault layer, with no fault).
ParticipantOptions counted(const char* name)
{
  ParticipantOptions options = test::sideBySide(name, kDomain);
  options.fault_layer = true;
  return options;
}

TEST(SimPeriod, AReaderTakesTheFirstSampleOfEachPeriodAndTheWriterSendsItNoOther)
{
  // GIVEN a plant writing states, a viewer asking for one a 40 ms of sim time, and a reader of
  // every one; the two readers' participants count the datagrams they receive
  Participant plant(test::sideBySide("plant", kDomain));
  Participant viewer(counted("viewer"));
  Participant scorer(counted("scorer"));
  Publisher<msg::VehicleState> states(plant, topics::kSimState);
  const auto every = withDepth(scorer.readerQos(topics::kSimState.info), 512);
  Subscriber<msg::VehicleState> all(scorer, topics::kSimState, nullptr, every);
  Subscriber<msg::VehicleState> decimated(viewer, topics::kSimState, nullptr, withMinimumSeparation(every, 40'000'000));
  ASSERT_TRUE(test::waitFor(
      [&] { return states.matchedReaders() == 2 && all.matchedWriters() == 1 && decimated.matchedWriters() == 1; }));
  std::this_thread::sleep_for(kReaderMatchSettle);  // the writer learns the viewer's filter with it

  // WHEN one second of sim time is written at 250 Hz
  const auto viewer_before = viewer.datagramFaults()->counts().seen;
  const auto scorer_before = scorer.datagramFaults()->counts().seen;
  constexpr int kStates = 250;
  for (int i = 0; i < kStates; ++i) {
    msg::VehicleState s;
    s.header().stamp_ns(std::int64_t{i} * 4'000'000);
    ASSERT_TRUE(states.write(s));
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // best effort: no burst to lose
  }
  std::vector<std::int64_t> every_stamp;
  std::vector<std::int64_t> decimated_stamps;
  test::waitFor([&] {
    for (const auto& s : all.takeAll()) {
      every_stamp.push_back(s.header().stamp_ns());
    }
    for (const auto& s : decimated.takeAll()) {
      decimated_stamps.push_back(s.header().stamp_ns());
    }
    return every_stamp.size() == kStates && decimated_stamps.size() == kStates / 10;
  });

  // THEN the viewer took the states stamped 0, 40, ..., 960 ms, the other reader all of them
  std::vector<std::int64_t> expected;
  for (std::int64_t t = 0; t < std::int64_t{kStates} * 4'000'000; t += 40'000'000) {
    expected.push_back(t);
  }
  EXPECT_EQ(decimated_stamps, expected);
  EXPECT_EQ(every_stamp.size(), static_cast<std::size_t>(kStates));
  // AND the nine states in ten it did not take never reached its participant: the writer
  // filtered them out (the rest of both counts is the same discovery traffic)
  const auto viewer_got = viewer.datagramFaults()->counts().seen - viewer_before;
  const auto scorer_got = scorer.datagramFaults()->counts().seen - scorer_before;
  EXPECT_GE(scorer_got, static_cast<std::uint64_t>(kStates));
  EXPECT_LT(viewer_got, scorer_got / 4) << "viewer " << viewer_got << ", scorer " << scorer_got;
}

}  // namespace
}  // namespace quad::dds
