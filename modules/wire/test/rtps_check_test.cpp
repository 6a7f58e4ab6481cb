// SPDX-License-Identifier: BSD-3-Clause
// The RTPS structure checks: well-formed messages pass, each kind of defect is caught, and
// the regression datagrams that end a Fast DDS 2.9 participant are refused.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "quad/wire/rtps_check.hpp"
#include "rtps_builder.hpp"

namespace quad::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// A discovery DATA: writer SN 1, PL_CDR_LE payload with a topic name and a GUID.
Bytes discoveryData(const std::string& topic = "quad/sim/state")
{
  test::RtpsBuilder m;
  m.begin(0x15, 0x04);  // D flag
  m.dataHeader(0x000003c2, 1);
  m.u8(0x00);
  m.u8(0x03);  // PL_CDR_LE
  m.u16(0);
  m.parameter(0x0005, [&] { m.string(topic); });  // PID_TOPIC_NAME
  m.parameter(0x0050, [&] { m.fill(16, 1); });    // PID_PARTICIPANT_GUID
  m.sentinel();
  m.end();
  return m.bytes();
}

Bytes heartbeat(std::int64_t first, std::int64_t last)
{
  test::RtpsBuilder m;
  m.begin(0x07, 0);
  m.entity(0);
  m.entity(0x00000102);
  m.sn(first);
  m.sn(last);
  m.u32(1);
  m.end();
  return m.bytes();
}

/// A DATA_FRAG: fragments [start, start + count) of `sample` bytes cut in `size`.
Bytes dataFrag(std::uint32_t start, std::uint16_t count, std::uint16_t size, std::uint32_t sample,
               std::size_t carried, std::uint16_t to_inline_qos = 28)
{
  test::RtpsBuilder m;
  m.begin(0x16, 0);
  m.dataHeader(0x00000102, 1, to_inline_qos);
  m.u32(start);
  m.u16(count);
  m.u16(size);
  m.u32(sample);
  m.fill(carried, 0xab);
  m.end();
  return m.bytes();
}

std::optional<RtpsDefect> check(const Bytes& b) { return checkRtpsDatagram(b.data(), b.size()); }

TEST(RtpsCheck, WellFormedMessagesPass)
{
  EXPECT_FALSE(check(discoveryData()));
  EXPECT_FALSE(check(heartbeat(1, 0)));  // an empty writer's
  EXPECT_FALSE(check(heartbeat(3, 40)));
  EXPECT_FALSE(check(dataFrag(1, 2, 1000, 2500, 2000)));
  EXPECT_FALSE(check(dataFrag(3, 1, 1000, 2500, 500)));  // the short last fragment
  Bytes two = heartbeat(1, 5);  // two submessages back to back
  const Bytes second = discoveryData();
  two.insert(two.end(), second.begin() + 20, second.end());
  EXPECT_FALSE(check(two));
}

TEST(RtpsCheck, HeaderDefectsAreCaught)
{
  Bytes b = heartbeat(1, 1);
  EXPECT_TRUE(check(Bytes(b.begin(), b.begin() + 19)));
  Bytes wrong = b;
  wrong[0] = 'X';
  EXPECT_TRUE(check(wrong));
  Bytes v1 = b;
  v1[4] = 1;
  EXPECT_TRUE(check(v1));
  EXPECT_TRUE(check(Bytes(b.begin(), b.begin() + 20)));  // no submessage
  EXPECT_TRUE(check(Bytes(b.begin(), b.begin() + 22)));  // half a submessage header
}

TEST(RtpsCheck, ASubmessageLongerThanTheDatagramIsCaught)
{
  Bytes b = heartbeat(1, 1);
  b[22] = 200;  // length 200, 28 present
  const auto d = check(b);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->offset, 20u);
  EXPECT_NE(d->what.find("HEARTBEAT"), std::string::npos) << d->what;
  Bytes cut = heartbeat(1, 1);
  cut[22] = 20;  // a HEARTBEAT too short for its fields
  cut.resize(44);
  EXPECT_TRUE(check(cut));
}

TEST(RtpsCheck, SequenceNumbersTheSpecificationForbidsAreCaught)
{
  EXPECT_TRUE(check(heartbeat(0, 5)));
  EXPECT_TRUE(check(heartbeat(10, 5)));
  EXPECT_TRUE(check(heartbeat(-1, 5)));
}

TEST(RtpsCheck, InconsistentFragmentsAreCaught)
{
  EXPECT_TRUE(check(dataFrag(0, 1, 1000, 2500, 1000)));     // fragment 0
  EXPECT_TRUE(check(dataFrag(3, 2, 1000, 2500, 1000)));     // fragments 3..4 of 3
  EXPECT_TRUE(check(dataFrag(1, 1, 0, 2500, 0)));           // fragment size 0
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 0, 0)));           // empty sample
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 2500, 1400)));     // more bytes than one fragment
  EXPECT_TRUE(check(dataFrag(3, 1, 1000, 2500, 900)));      // past the end of the sample
  EXPECT_TRUE(check(dataFrag(1, 1, 60000, 1u << 30, 100)));  // a 1 GiB reassembly
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 2500, 100, 0)));   // inline QoS inside its own fields
}

TEST(RtpsCheck, ParameterListDefectsAreCaught)
{
  // The payload's first parameter, the topic name: id at byte 48, length at 50, value at 52.
  const Bytes good = discoveryData();
  ASSERT_FALSE(check(good));
  Bytes other_id = good;
  other_id[48] = 0x06;  // a parameter whose value is not looked into keeps the list valid...
  EXPECT_FALSE(check(other_id));
  Bytes unaligned = good;
  unaligned[50] = static_cast<std::uint8_t>(unaligned[50] + 1);  // ...a length not a multiple of 4 does not
  EXPECT_TRUE(check(unaligned));
  Bytes too_long = good;
  too_long[50] = 0xfc;
  EXPECT_TRUE(check(too_long));
  Bytes string_past = good;
  string_past[52] = 0xff;  // the topic string's length runs past its parameter
  const auto d = check(string_past);
  ASSERT_TRUE(d);
  EXPECT_NE(d->what.find("0x0005"), std::string::npos) << d->what;
  Bytes no_sentinel = good;
  no_sentinel.resize(no_sentinel.size() - 4);
  no_sentinel[22] = static_cast<std::uint8_t>(no_sentinel[22] - 4);
  EXPECT_TRUE(check(no_sentinel));
}

TEST(RtpsCheck, OnlyDiscoveryPayloadsAreReadAsParameterLists)
{
  // The liveliness writer's ParticipantMessageData claims PL_CDR_LE but is plain CDR (its
  // GUID prefix starts with the vendor id): read as a parameter list it would look broken.
  Bytes liveliness = discoveryData();
  liveliness[33] = 0x02;
  liveliness[34] = 0x00;  // writer 0x000200c2
  liveliness[50] = 0xfc;  // "parameter" length 252: garbage for a parameter list
  EXPECT_FALSE(check(liveliness));
  Bytes discovery = discoveryData();
  discovery[50] = 0xfc;
  EXPECT_TRUE(check(discovery));
}

/// A user DATA with its key hash in the inline QoS (writer 0x00000102: a keyed user writer):
/// the hash names vehicle `hashed`, the CDR payload's Header.vehicle_id is `carried`.
Bytes keyedSample(std::uint32_t hashed, std::uint32_t carried, std::uint32_t writer = 0x00000102,
                  std::uint8_t encapsulation = 0x01)
{
  test::RtpsBuilder m;
  m.begin(0x15, 0x02 | 0x04);  // Q and D flags
  m.dataHeader(writer, 7);
  m.parameter(0x0070, [&] {  // PID_KEY_HASH: the id big-endian, zero-padded
    m.entity(hashed);
    m.fill(12, 0);
  });
  m.sentinel();
  m.u8(0x00);
  m.u8(encapsulation);
  m.u16(0);
  if (encapsulation == 0x01) {
    m.u32(carried);
  } else {
    m.entity(carried);  // big-endian
  }
  m.fill(20, 0x5a);  // the rest of the sample
  m.end();
  return m.bytes();
}

TEST(RtpsCheck, AKeyHashMustBeThePayloadsKey)
{
  EXPECT_FALSE(check(keyedSample(3, 3)));
  EXPECT_FALSE(check(keyedSample(0, 0)));
  EXPECT_FALSE(check(keyedSample(70000, 70000, 0x00000102, 0x00)));  // CDR_BE
  // One damaged bit, in the hash or in the payload's vehicle id, and Fast DDS would file the
  // sample under an instance nobody wrote.
  const auto d = check(keyedSample(0x80000000u, 0));
  ASSERT_TRUE(d);
  EXPECT_NE(d->what.find("key hash 80000000"), std::string::npos) << d->what;
  EXPECT_NE(d->what.find("vehicle 0"), std::string::npos) << d->what;
  EXPECT_TRUE(check(keyedSample(1, 0x01000001)));
  // Keyless writers' samples (Foxglove's) have no key to compare.
  EXPECT_FALSE(check(keyedSample(1, 2, 0x00000103)));
}

TEST(RtpsCheck, AFirstFragmentsKeyHashMustBeThePayloadsKey)
{
  const auto fragment = [](std::uint32_t start, std::uint32_t carried) {
    test::RtpsBuilder m;
    m.begin(0x16, 0x02);  // Q flag
    m.dataHeader(0x00000102, 1, 28);
    m.u32(start);
    m.u16(1);
    m.u16(64);
    m.u32(128);
    m.parameter(0x0070, [&] {
      m.entity(5);
      m.fill(12, 0);
    });
    m.sentinel();
    if (start == 1) {
      m.u8(0x00);
      m.u8(0x01);  // CDR_LE
      m.u16(0);
      m.u32(carried);
      m.fill(56, 0x5a);
    } else {
      m.fill(64, 0x5a);
    }
    m.end();
    return m.bytes();
  };
  EXPECT_FALSE(check(fragment(1, 5)));
  EXPECT_TRUE(check(fragment(1, 4)));
  EXPECT_FALSE(check(fragment(2, 4)));  // no payload header in a later fragment
}

Bytes readFile(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(RtpsCheck, TheRegressionDatagramsThatEndAParticipantAreRefused)
{
  const std::filesystem::path dir = QUAD_DATAGRAMS_DIR;
  for (const char* name : {"20140.bin", "23833.bin", "23834.bin"}) {
    const Bytes b = readFile(dir / name);
    ASSERT_FALSE(b.empty()) << name;
    const auto d = check(b);
    EXPECT_TRUE(d) << name << " passed";
    if (d) {
      std::cout << name << ": at byte " << d->offset << ": " << d->what << "\n";
    }
  }
}

TEST(RtpsCheck, RandomBytesNeverReadPastTheDatagram)
{
  // Under the sanitizers this is a small fuzzer: mutations of well-formed messages, each
  // checked in a buffer of exactly its size.
  std::mt19937 rng(7);
  const std::vector<Bytes> seeds = {discoveryData(), heartbeat(1, 9), dataFrag(1, 2, 500, 1200, 1000)};
  int refused = 0;
  for (int i = 0; i < 20000; ++i) {
    Bytes b = seeds[static_cast<std::size_t>(i) % seeds.size()];
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) {
      b[rng() % b.size()] = static_cast<std::uint8_t>(rng());
    }
    if (rng() % 4 == 0) {
      b.resize(rng() % b.size());
    }
    auto heap = std::make_unique<std::uint8_t[]>(b.size());
    std::copy(b.begin(), b.end(), heap.get());
    refused += checkRtpsDatagram(heap.get(), b.size()) ? 1 : 0;
  }
  EXPECT_GT(refused, 5000);  // most mutations break something
}

}  // namespace
}  // namespace quad::wire
