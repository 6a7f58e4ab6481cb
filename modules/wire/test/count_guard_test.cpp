// SPDX-License-Identifier: BSD-3-Clause
// Counts a receiver only lets grow: read from datagrams, and leaps refused unless confirmed.
#include "quad/wire/count_guard.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rtps_builder.hpp"

namespace quad::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::int64_t kSecond = 1'000'000'000;

/// A HEARTBEAT of writer 0x102 with `count`, from GUID prefix 1, 2, ...; with `info_src`, an
/// INFO_SRC naming prefix 9, 10, ... comes first.
Bytes heartbeat(std::uint32_t count, bool info_src = false)
{
  test::RtpsBuilder m;
  if (info_src) {
    m.begin(0x0c, 0);
    m.u32(0);
    m.u8(2);
    m.u8(3);
    m.u16(0x0f01);
    for (std::uint8_t i = 0; i < 12; ++i) {
      m.u8(static_cast<std::uint8_t>(9 + i));
    }
    m.end();
  }
  m.begin(0x07, 0);
  m.entity(0);
  m.entity(0x00000102);
  m.sn(1);
  m.sn(5);
  m.u32(count);
  m.end();
  return m.bytes();
}

/// An ACKNACK of reader 0x107 to writer 0x102 with a 40-bit set and `count`.
Bytes acknack(std::uint32_t count)
{
  test::RtpsBuilder m;
  m.begin(0x06, 0);
  m.entity(0x00000107);
  m.entity(0x00000102);
  m.sn(3);
  m.u32(40);
  m.u32(0xffffffff);
  m.u32(0xff);
  m.u32(count);
  m.end();
  return m.bytes();
}

std::vector<RtpsCount> countsOf(const Bytes& b)
{
  std::vector<RtpsCount> counts;
  EXPECT_FALSE(checkRtpsDatagram(b.data(), b.size(), &counts));
  return counts;
}

TEST(RtpsCounts, AreReadWithTheirSenderAndEndpoints)
{
  const auto hb = countsOf(heartbeat(28));
  ASSERT_EQ(hb.size(), 1U);
  EXPECT_EQ(hb[0].kind, 0x07);
  EXPECT_EQ(hb[0].count, 28U);
  EXPECT_EQ(hb[0].writer_id, 0x00000102U);
  EXPECT_EQ(hb[0].prefix[0], 1);
  const auto relayed = countsOf(heartbeat(28, true));
  ASSERT_EQ(relayed.size(), 1U);
  EXPECT_EQ(relayed[0].prefix[0], 9) << "INFO_SRC names the sender";
  const auto ack = countsOf(acknack(7));
  ASSERT_EQ(ack.size(), 1U);
  EXPECT_EQ(ack[0].count, 7U);
  EXPECT_EQ(ack[0].reader_id, 0x00000107U);
}

TEST(CountGuard, ABitFlippedHighInAHeartbeatCountIsLoweredAndTheWriterKeepsBeingHeard)
{
  CountGuard guard;
  std::int64_t t = kSecond;
  for (std::uint32_t c = 1; c <= 28; ++c, t += kSecond / 10) {
    ASSERT_TRUE(guard.admit(countsOf(heartbeat(c)), t).empty()) << c;
  }
  // The datagram seen in a corrupted run: bit 28 of the count flipped. It goes on as 29.
  Bytes damaged = heartbeat(28 | (1U << 28));
  const auto tamings = guard.admit(countsOf(damaged), t);
  ASSERT_EQ(tamings.size(), 1U);
  EXPECT_EQ(tamings[0].count.count, 268'435'484U);
  EXPECT_EQ(tamings[0].replaced, 29U);
  EXPECT_FALSE(tamings[0].first);
  CountGuard::apply(tamings, damaged.data());
  EXPECT_EQ(countsOf(damaged).at(0).count, 29U);
  // The writer's own next heartbeats rise above it and pass untouched.
  EXPECT_TRUE(guard.admit(countsOf(heartbeat(30)), t + kSecond / 10).empty());
  EXPECT_TRUE(guard.admit(countsOf(heartbeat(31)), t + 2 * kSecond / 10).empty());
}

TEST(CountGuard, ALeapTheSenderContinuesFromIsFollowedThere)
{
  // A writer met for the first time after a day of heartbeats, or a burst of fragments
  // whose middle a socket buffer dropped: the first count leaps, the next confirms it.
  CountGuard guard;
  const auto met = guard.admit(countsOf(heartbeat(864'000)), kSecond);
  ASSERT_EQ(met.size(), 1U);
  EXPECT_TRUE(met[0].first);  // told apart: a late joiner meets this at every running writer
  EXPECT_TRUE(guard.admit(countsOf(heartbeat(864'001)), kSecond + kSecond / 10).empty());
  EXPECT_TRUE(guard.admit(countsOf(heartbeat(864'002)), kSecond + 2 * kSecond / 10).empty());
  // Leaps that nothing continues are lowered each time, one above the last passed on.
  const auto first = guard.admit(countsOf(heartbeat(5'000'000)), 2 * kSecond);
  ASSERT_EQ(first.size(), 1U);
  EXPECT_EQ(first[0].replaced, 864'003U);
  EXPECT_FALSE(first[0].first);
  const auto second = guard.admit(countsOf(heartbeat(9'000'000)), 2 * kSecond + kSecond / 10);
  ASSERT_EQ(second.size(), 1U);
  EXPECT_EQ(second[0].replaced, 864'004U);
  EXPECT_TRUE(guard.admit(countsOf(heartbeat(864'005)), 2 * kSecond + 2 * kSecond / 10).empty());
}

TEST(CountGuard, TheAllowedLeapGrowsWithTheTimeSinceTheSendersLastCount)
{
  CountGuard guard;
  ASSERT_TRUE(guard.admit(countsOf(acknack(1)), kSecond).empty());
  // Ten seconds without a datagram from it (a partition): up to 64 + 10,000 more.
  EXPECT_TRUE(guard.admit(countsOf(acknack(9'000)), 11 * kSecond).empty());
  EXPECT_EQ(guard.admit(countsOf(acknack(9'000 + 64 + 1'000)), 11 * kSecond + kSecond / 1000 * 999).size(), 1U);
  // Stale and repeated counts are the receiver's to ignore, not a leap.
  EXPECT_TRUE(guard.admit(countsOf(acknack(3)), 12 * kSecond).empty());
}

}  // namespace
}  // namespace quad::wire
