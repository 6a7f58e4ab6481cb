// SPDX-License-Identifier: BSD-3-Clause
// A reader's minimum separation in sim time: which samples the filter lets through, and what
// its factory accepts.
#include "quad/dds/sim_period_filter.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include <fastdds/dds/core/StackAllocatedSequence.hpp>

#include "quad/dds/message_types.hpp"

namespace quad::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

constexpr std::int64_t kStepNs = 4'000'000;  // the plant's 250 Hz

TEST(SimPeriodGate, EachPeriodAlignedWindowPassesItsFirstSampleOnly)
{
  SimPeriodGate gate(20'000'000);
  std::vector<std::int64_t> passed;
  for (std::int64_t t = 0; t <= 100'000'000; t += kStepNs) {
    if (gate.pass(0, t)) {
      passed.push_back(t);
    }
  }
  // Windows [0,20), [20,40), ...: 0, 20, 40, 60, 80 and 100 ms are each the first of theirs.
  EXPECT_EQ(passed, (std::vector<std::int64_t>{0, 20'000'000, 40'000'000, 60'000'000, 80'000'000, 100'000'000}));
}

TEST(SimPeriodGate, ForAnyStampsItPassesOnePerWindowEntered)
{
  // Random increasing stamps with gaps longer and shorter than the period, and none (a
  // sample sent again): a sample passes exactly when its window differs from the previous
  // sample's, or it is stamped as the last one passed.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> gap(0, 45'000'000);
  constexpr std::int64_t kPeriod = 10'000'000;
  SimPeriodGate gate(kPeriod);
  std::int64_t t = 3;
  std::int64_t last_window = -1;
  std::int64_t last_passed = -1;
  for (int i = 0; i < 5000; ++i) {
    t += gap(rng) < 4'000'000 ? 0 : gap(rng);
    const std::int64_t window = t / kPeriod;
    const bool passes = window != last_window || t == last_passed;
    EXPECT_EQ(gate.pass(2, t), passes) << "stamp " << t;
    last_window = window;
    last_passed = passes ? t : last_passed;
  }
}

TEST(SimPeriodGate, VehiclesAreFilteredApartAndAClockThatStartsAgainOpensWindowsAgain)
{
  SimPeriodGate gate(20'000'000);
  EXPECT_TRUE(gate.pass(1, 0));
  EXPECT_TRUE(gate.pass(2, 4'000'000));  // vehicle 2's first
  EXPECT_FALSE(gate.pass(1, 4'000'000));
  EXPECT_FALSE(gate.pass(2, 8'000'000));
  EXPECT_TRUE(gate.pass(1, 500'000'000));
  EXPECT_TRUE(gate.pass(1, 0));  // earlier than the last: another window
  EXPECT_FALSE(gate.pass(1, 4'000'000));
}

TEST(SimPeriodGate, ASamplePassedIsPassedAgainWhenSentAgain)
{
  // A lockstep plant resends its clock while it waits: a reader that matched after the first
  // copy went out must still take the time.
  SimPeriodGate gate(20'000'000);
  EXPECT_TRUE(gate.pass(0, 0));
  EXPECT_TRUE(gate.pass(0, 0));
  EXPECT_FALSE(gate.pass(0, 4'000'000));
  EXPECT_FALSE(gate.pass(0, 4'000'000));  // never passed: not sent again to this reader either
  EXPECT_TRUE(gate.pass(0, 0));           // still the last one passed
  EXPECT_TRUE(gate.pass(0, 20'000'000));
  EXPECT_TRUE(gate.pass(0, 20'000'000));
}

TEST(SimPeriodWindowEnd, IsTheStartOfTheNextWindowBeforeZeroToo)
{
  constexpr std::int64_t kPeriod = 20'000'000;
  EXPECT_EQ(simPeriodWindowEnd(0, kPeriod), kPeriod);
  EXPECT_EQ(simPeriodWindowEnd(kPeriod - 1, kPeriod), kPeriod);
  EXPECT_EQ(simPeriodWindowEnd(kPeriod, kPeriod), 2 * kPeriod);
  EXPECT_EQ(simPeriodWindowEnd(-1, kPeriod), 0);
  EXPECT_EQ(simPeriodWindowEnd(-kPeriod, kPeriod), 0);
  // No sample the gate passes after one of a window falls before its end, unless a new one opens.
  SimPeriodGate gate(kPeriod);
  for (std::int64_t t = 0; t < 10 * kPeriod; t += kStepNs) {
    if (gate.pass(0, t)) {
      for (std::int64_t u = t + 1; u < simPeriodWindowEnd(t, kPeriod); u += 1'000'000) {
        EXPECT_FALSE(gate.pass(0, u)) << t << " then " << u;
      }
    }
  }
}

TEST(SimPeriodGate, RefusesAPeriodThatIsNotPositive)
{
  EXPECT_THROW(SimPeriodGate(0), std::invalid_argument);
  EXPECT_THROW(SimPeriodGate(-5), std::invalid_argument);
}

void deleteFilter(fdds::IContentFilter* filter)
{
  simPeriodFilterFactory().delete_content_filter(kSimPeriodFilterClass, filter);
}

/// The factory's answer to an expression and parameters; the filter made, if any.
struct Made {
  ReturnCode_t code;
  std::unique_ptr<fdds::IContentFilter, void (*)(fdds::IContentFilter*)> filter{nullptr, &deleteFilter};
};

Made make(const char* expression, std::vector<const char*> parameters)
{
  fdds::StackAllocatedSequence<const char*, 4> seq;
  seq.length(static_cast<fdds::LoanableCollection::size_type>(parameters.size()));
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    seq[static_cast<fdds::LoanableCollection::size_type>(i)] = parameters[i];
  }
  fdds::IContentFilter* filter = nullptr;
  Made m{simPeriodFilterFactory().create_content_filter(kSimPeriodFilterClass, "quad::msg::VehicleState", nullptr,
                                                         expression, seq, filter)};
  m.filter.reset(filter);
  return m;
}

TEST(SimPeriodFilterFactory, AcceptsItsExpressionWithOnePositiveIntegerPeriodOnly)
{
  EXPECT_EQ(make(kSimPeriodFilterExpression, {"20000000"}).code, ReturnCode_t::RETCODE_OK);
  EXPECT_EQ(make("Header.stamp_ns > 5", {"20000000"}).code, ReturnCode_t::RETCODE_BAD_PARAMETER);
  EXPECT_EQ(make(kSimPeriodFilterExpression, {}).code, ReturnCode_t::RETCODE_BAD_PARAMETER);
  EXPECT_EQ(make(kSimPeriodFilterExpression, {"20000000", "1"}).code, ReturnCode_t::RETCODE_BAD_PARAMETER);
  for (const char* bad : {"0", "-4", "20ms", "", "1e7", "99999999999999999999"}) {
    EXPECT_EQ(make(kSimPeriodFilterExpression, {bad}).code, ReturnCode_t::RETCODE_BAD_PARAMETER) << bad;
  }
}

TEST(SimPeriodFilterFactory, TheFilterReadsTheStampAndVehicleFromTheSerializedSample)
{
  Made m = make(kSimPeriodFilterExpression, {"20000000"});
  ASSERT_EQ(m.code, ReturnCode_t::RETCODE_OK);
  MessageTraits<msg::VehicleState>::PubSubType type;
  const auto passes = [&](std::uint32_t vehicle, std::int64_t stamp) {
    msg::VehicleState s;
    s.header().vehicle_id(vehicle);
    s.header().stamp_ns(stamp);
    eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&s)());
    EXPECT_TRUE(type.serialize(&s, &payload));
    return m.filter->evaluate(payload, {}, {});
  };
  EXPECT_TRUE(passes(0, 0));
  EXPECT_FALSE(passes(0, 4'000'000));
  EXPECT_TRUE(passes(5, 4'000'000));
  EXPECT_TRUE(passes(0, 20'000'000));
  // A payload with no Header to read is not the filter's to drop.
  eprosima::fastrtps::rtps::SerializedPayload_t empty(0);
  EXPECT_TRUE(m.filter->evaluate(empty, {}, {}));
}

TEST(MinimumSeparation, IsCarriedInTheReaderQosTimeBasedFilter)
{
  const fdds::DataReaderQos qos = withMinimumSeparation(fdds::DataReaderQos(), 1'500'000'000);
  EXPECT_EQ(qos.time_based_filter().minimum_separation.seconds, 1);
  EXPECT_EQ(qos.time_based_filter().minimum_separation.nanosec, 500'000'000U);
  EXPECT_EQ(minimumSeparationNs(qos), 1'500'000'000);
  EXPECT_EQ(minimumSeparationNs(fdds::DataReaderQos()), 0);
  EXPECT_THROW(withMinimumSeparation(fdds::DataReaderQos(), -1), std::invalid_argument);
  // A deadline a sample a period would miss is widened to two periods; a longer one is kept.
  fdds::DataReaderQos tight;
  tight.deadline().period = eprosima::fastrtps::Duration_t(0, 8'000'000);
  EXPECT_EQ(withMinimumSeparation(tight, 20'000'000).deadline().period.to_ns(), 40'000'000);
  EXPECT_EQ(withMinimumSeparation(tight, 0).deadline().period.to_ns(), 8'000'000);
  fdds::DataReaderQos loose;
  loose.deadline().period = eprosima::fastrtps::Duration_t(1, 0);
  EXPECT_EQ(withMinimumSeparation(loose, 20'000'000).deadline().period.to_ns(), 1'000'000'000);
}

}  // namespace
}  // namespace quad::dds
