// SPDX-License-Identifier: BSD-3-Clause
// Loss accounting from writers' sequence numbers.
#include "quad/bag/audit.hpp"

#include <gtest/gtest.h>

namespace quad::bag {
namespace {

TEST(SequenceAudit, CountsGapsDuplicatesAndReorderingPerWriter)
{
  SequenceAudit a;
  for (const std::uint64_t s : {5U, 6U, 7U, 9U, 10U, 10U, 8U, 12U}) {  // joins at 5; 8 late; 10 twice; 11 never
    a.add(1, 0, s);
  }
  for (std::uint64_t s = 1; s <= 100; ++s) {  // another writer, interleaved numbers of its own
    a.add(2, 0, s);
  }
  const LossFigures f = a.figures();
  EXPECT_EQ(f.received, 108U);
  EXPECT_EQ(f.missing, 1U);
  EXPECT_EQ(f.duplicated, 1U);
  EXPECT_EQ(f.reordered, 1U);
  EXPECT_EQ(a.writers(), 2U);
}

TEST(SequenceAudit, AWriterOfSeveralVehiclesNumbersEachOnItsOwn)
{
  SequenceAudit a;
  for (std::uint64_t s = 1; s <= 50; ++s) {  // one writer, a fleet's three vehicles interleaved
    for (const std::uint32_t vehicle : {1U, 2U, 3U}) {
      if (!(vehicle == 2 && s == 20)) {  // vehicle 2's 20th lost
        a.add(9, vehicle, s);
      }
    }
  }
  const LossFigures f = a.figures();
  EXPECT_EQ(f.received, 149U);
  EXPECT_EQ(f.missing, 1U);
  EXPECT_EQ(f.duplicated + f.reordered, 0U);
  EXPECT_EQ(a.writers(), 1U);
}

TEST(SequenceAudit, AnUnbrokenRunHasNoLoss)
{
  SequenceAudit a;
  for (std::uint64_t s = 1; s <= 1000; ++s) {
    a.add(7, 0, s);
  }
  const LossFigures f = a.figures();
  EXPECT_EQ(f.received, 1000U);
  EXPECT_EQ(f.missing + f.duplicated + f.reordered, 0U);
}

TEST(LossFigures, TextRoundTripsAndOtherTextIsRefused)
{
  const LossFigures f{.received = 120, .missing = 3, .duplicated = 1, .reordered = 2};
  const std::string text = toText(f, 2);
  EXPECT_EQ(text, "received 120 missing 3 duplicated 1 reordered 2 writers 2");
  const auto back = parseLossFigures(text);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->received, 120U);
  EXPECT_EQ(back->missing, 3U);
  EXPECT_EQ(back->duplicated, 1U);
  EXPECT_EQ(back->reordered, 2U);
  EXPECT_EQ(parseLossWriters(text), 2U);
  EXPECT_FALSE(parseLossWriters("received 1 missing 0 duplicated 0 reordered 0").has_value());
  EXPECT_FALSE(parseLossFigures("(not recorded)").has_value());
  EXPECT_FALSE(parseLossFigures("received 1 lost 2").has_value());
}

}  // namespace
}  // namespace quad::bag
