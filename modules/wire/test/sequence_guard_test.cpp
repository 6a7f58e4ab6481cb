// SPDX-License-Identifier: BSD-3-Clause
// A writer's sequence numbers, read from datagrams: a GAP far past what its writer stated is
// refused, and a leap is believed only when the writer's next number continues from it.
#include "quad/wire/sequence_guard.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rtps_builder.hpp"

namespace quad::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::uint32_t kWriter = 0x00000102;

Bytes heartbeat(std::int64_t first, std::int64_t last, std::uint32_t count = 1)
{
  test::RtpsBuilder m;
  m.begin(0x07, 0);
  m.entity(0);
  m.entity(kWriter);
  m.sn(first);
  m.sn(last);
  m.u32(count);
  m.end();
  return m.bytes();
}

/// A GAP of [start, base) and `bits` more after base, all set.
Bytes gap(std::int64_t start, std::int64_t base, std::uint32_t bits = 0)
{
  test::RtpsBuilder m;
  m.begin(0x08, 0);
  m.entity(0);
  m.entity(kWriter);
  m.sn(start);
  m.sn(base);
  m.u32(bits);
  for (std::uint32_t w = 0; w < (bits + 31) / 32; ++w) {
    m.u32(0xffffffff);
  }
  m.end();
  return m.bytes();
}

Bytes data(std::int64_t sn)
{
  test::RtpsBuilder m;
  m.begin(0x15, 0x04);
  m.dataHeader(kWriter, sn);
  m.u8(0x00);
  m.u8(0x01);
  m.u16(0);
  m.u32(0);
  m.end();
  return m.bytes();
}

std::vector<RtpsSequence> sequencesOf(const Bytes& b)
{
  std::vector<RtpsSequence> sequences;
  EXPECT_FALSE(checkRtpsDatagram(b.data(), b.size(), nullptr, &sequences));
  return sequences;
}

TEST(RtpsSequences, AreReadForEachKindThatStatesOne)
{
  const auto hb = sequencesOf(heartbeat(3, 40));
  ASSERT_EQ(hb.size(), 1U);
  EXPECT_EQ(hb[0].last, 40);
  EXPECT_EQ(hb[0].writer_id, kWriter);
  EXPECT_EQ(hb[0].prefix[0], 1);
  const auto d = sequencesOf(data(17));
  ASSERT_EQ(d.size(), 1U);
  EXPECT_EQ(d[0].last, 17);
  EXPECT_EQ(d[0].writer_id, kWriter);
  const auto g = sequencesOf(gap(5, 9, 40));
  ASSERT_EQ(g.size(), 1U);
  EXPECT_EQ(g[0].last, 9 - 1 + 40) << "a GAP's reach: its list's base and bits";
}

TEST(SequenceGuard, AGapWithinWhatTheWriterStatedPasses)
{
  SequenceGuard guard;
  const std::int64_t t = 5 * kSecond;
  EXPECT_FALSE(guard.admit(sequencesOf(heartbeat(1, 500)), t));
  EXPECT_FALSE(guard.admit(sequencesOf(gap(100, 400, 64)), t + kSecond / 10));
  // It may have written on since: the slack and its rate over the time since.
  EXPECT_FALSE(guard.admit(sequencesOf(gap(400, 500 + SequenceGuard::kSlack)), t + kSecond / 10));
  EXPECT_FALSE(guard.admit(sequencesOf(gap(400, 500 + 10'000)), t + kSecond));
}

TEST(SequenceGuard, AGapFarPastWhatTheWriterStatedIsRefused)
{
  SequenceGuard guard;
  const std::int64_t t = 5 * kSecond;
  EXPECT_FALSE(guard.admit(sequencesOf(data(300)), t));
  // Bit 31 of the list's base flipped: two billion sequence numbers for Fast DDS to walk.
  const auto d = guard.admit(sequencesOf(gap(290, 300 + (std::int64_t{1} << 31))), t + kSecond / 10);
  ASSERT_TRUE(d);
  EXPECT_NE(d->what.find("GAP from writer 0x00000102"), std::string::npos) << d->what;
  EXPECT_NE(d->what.find("stated 300"), std::string::npos) << d->what;
}

TEST(SequenceGuard, AWriterFirstHeardThroughAGapIsNotJudged)
{
  SequenceGuard guard;
  EXPECT_FALSE(guard.admit(sequencesOf(gap(1, 1'000'000'000)), kSecond));
}

TEST(SequenceGuard, ALeapIsBelievedOnlyWhenTheWritersNextNumberContinuesIt)
{
  SequenceGuard guard;
  const std::int64_t t = 5 * kSecond;
  const std::int64_t leap = 500 + (std::int64_t{1} << 24);
  EXPECT_FALSE(guard.admit(sequencesOf(heartbeat(1, 500)), t));
  // A damaged HEARTBEAT passes on (Fast DDS copes with it) but does not open the way...
  EXPECT_FALSE(guard.admit(sequencesOf(heartbeat(1, leap)), t + kSecond / 10));
  EXPECT_TRUE(guard.admit(sequencesOf(gap(400, leap)), t + kSecond / 10));
  // ...while a writer that really got that far says so again, and is followed.
  EXPECT_FALSE(guard.admit(sequencesOf(heartbeat(1, leap + 3)), t + kSecond / 5));
  EXPECT_FALSE(guard.admit(sequencesOf(gap(400, leap)), t + kSecond / 5));
}

}  // namespace
}  // namespace quad::wire
