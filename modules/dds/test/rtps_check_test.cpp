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

#include "quad/dds/rtps_check.hpp"

namespace quad::dds {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// Little-endian message building.
struct Message {
  Bytes b;

  Message()
  {
    b = {'R', 'T', 'P', 'S', 2, 3, 0x01, 0x0f};
    for (int i = 0; i < 12; ++i) {
      b.push_back(static_cast<std::uint8_t>(i + 1));  // GUID prefix
    }
  }
  void u8(std::uint8_t v) { b.push_back(v); }
  void u16(std::uint16_t v)
  {
    b.push_back(static_cast<std::uint8_t>(v));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v)
  {
    u16(static_cast<std::uint16_t>(v));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  /// Entity ids are octets, big-endian whatever the submessage's order.
  void entity(std::uint32_t v)
  {
    for (int shift = 24; shift >= 0; shift -= 8) {
      u8(static_cast<std::uint8_t>(v >> shift));
    }
  }
  void sn(std::int64_t v)
  {
    u32(static_cast<std::uint32_t>(v >> 32));
    u32(static_cast<std::uint32_t>(v));
  }
  /// A submessage header, its length filled in by end().
  std::size_t begin(std::uint8_t id, std::uint8_t flags)
  {
    u8(id);
    u8(static_cast<std::uint8_t>(flags | 0x01));
    u16(0);
    return b.size();
  }
  void end(std::size_t body)
  {
    const auto length = static_cast<std::uint16_t>(b.size() - body);
    b[body - 2] = static_cast<std::uint8_t>(length);
    b[body - 1] = static_cast<std::uint8_t>(length >> 8);
  }
  void cdrString(const std::string& s)
  {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    for (char c : s) {
      u8(static_cast<std::uint8_t>(c));
    }
    u8(0);
    while (b.size() % 4 != 0) {
      u8(0);
    }
  }
};

/// A discovery DATA: writer SN 1, PL_CDR_LE payload with a topic name and a GUID.
Message discoveryData(const std::string& topic = "quad/sim/state")
{
  Message m;
  const std::size_t body = m.begin(0x15, 0x04);  // D flag
  m.u16(0);
  m.u16(16);
  m.entity(0);
  m.entity(0x000003c2);
  m.sn(1);
  m.u8(0x00);
  m.u8(0x03);  // PL_CDR_LE
  m.u16(0);
  m.u16(0x0005);  // PID_TOPIC_NAME
  const std::size_t length_at = m.b.size();
  m.u16(0);
  const std::size_t value = m.b.size();
  m.cdrString(topic);
  const auto length = static_cast<std::uint16_t>(m.b.size() - value);
  m.b[length_at] = static_cast<std::uint8_t>(length);
  m.b[length_at + 1] = static_cast<std::uint8_t>(length >> 8);
  m.u16(0x0050);  // PID_PARTICIPANT_GUID
  m.u16(16);
  for (int i = 0; i < 16; ++i) {
    m.u8(1);
  }
  m.u16(0x0001);  // PID_SENTINEL
  m.u16(0);
  m.end(body);
  return m;
}

Message heartbeat(std::int64_t first, std::int64_t last)
{
  Message m;
  const std::size_t body = m.begin(0x07, 0);
  m.entity(0);
  m.entity(0x00000102);
  m.sn(first);
  m.sn(last);
  m.u32(1);
  m.end(body);
  return m;
}

/// A DATA_FRAG: fragments [start, start + count) of `sample` bytes cut in `size`.
Message dataFrag(std::uint32_t start, std::uint16_t count, std::uint16_t size, std::uint32_t sample,
                 std::size_t carried, std::uint16_t to_inline_qos = 28)
{
  Message m;
  const std::size_t body = m.begin(0x16, 0);
  m.u16(0);
  m.u16(to_inline_qos);
  m.entity(0);
  m.entity(0x00000102);
  m.sn(1);
  m.u32(start);
  m.u16(count);
  m.u16(size);
  m.u32(sample);
  for (std::size_t i = 0; i < carried; ++i) {
    m.u8(0xab);
  }
  m.end(body);
  return m;
}

std::optional<RtpsDefect> check(const Bytes& b) { return checkRtpsDatagram(b.data(), b.size()); }

TEST(RtpsCheck, WellFormedMessagesPass)
{
  EXPECT_FALSE(check(discoveryData().b));
  EXPECT_FALSE(check(heartbeat(1, 0).b));  // an empty writer's
  EXPECT_FALSE(check(heartbeat(3, 40).b));
  EXPECT_FALSE(check(dataFrag(1, 2, 1000, 2500, 2000).b));
  EXPECT_FALSE(check(dataFrag(3, 1, 1000, 2500, 500).b));  // the short last fragment
  Message two = heartbeat(1, 5);  // two submessages back to back
  const Bytes second = discoveryData().b;
  two.b.insert(two.b.end(), second.begin() + 20, second.end());
  EXPECT_FALSE(check(two.b));
}

TEST(RtpsCheck, HeaderDefectsAreCaught)
{
  Bytes b = heartbeat(1, 1).b;
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
  Bytes b = heartbeat(1, 1).b;
  b[22] = 200;  // length 200, 28 present
  const auto d = check(b);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->offset, 20u);
  EXPECT_NE(d->what.find("HEARTBEAT"), std::string::npos) << d->what;
  Bytes cut = heartbeat(1, 1).b;
  cut[22] = 20;  // a HEARTBEAT too short for its fields
  cut.resize(44);
  EXPECT_TRUE(check(cut));
}

TEST(RtpsCheck, SequenceNumbersTheSpecificationForbidsAreCaught)
{
  EXPECT_TRUE(check(heartbeat(0, 5).b));
  EXPECT_TRUE(check(heartbeat(10, 5).b));
  EXPECT_TRUE(check(heartbeat(-1, 5).b));
}

TEST(RtpsCheck, InconsistentFragmentsAreCaught)
{
  EXPECT_TRUE(check(dataFrag(0, 1, 1000, 2500, 1000).b));     // fragment 0
  EXPECT_TRUE(check(dataFrag(3, 2, 1000, 2500, 1000).b));     // fragments 3..4 of 3
  EXPECT_TRUE(check(dataFrag(1, 1, 0, 2500, 0).b));           // fragment size 0
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 0, 0).b));           // empty sample
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 2500, 1400).b));     // more bytes than one fragment
  EXPECT_TRUE(check(dataFrag(3, 1, 1000, 2500, 900).b));      // past the end of the sample
  EXPECT_TRUE(check(dataFrag(1, 1, 60000, 1u << 30, 100).b));  // a 1 GiB reassembly
  EXPECT_TRUE(check(dataFrag(1, 1, 1000, 2500, 100, 0).b));   // inline QoS inside its own fields
}

TEST(RtpsCheck, ParameterListDefectsAreCaught)
{
  // The payload's first parameter, the topic name: id at byte 48, length at 50, value at 52.
  const Bytes good = discoveryData().b;
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
  Bytes liveliness = discoveryData().b;
  liveliness[33] = 0x02;
  liveliness[34] = 0x00;  // writer 0x000200c2
  liveliness[50] = 0xfc;  // "parameter" length 252: garbage for a parameter list
  EXPECT_FALSE(check(liveliness));
  Bytes discovery = discoveryData().b;
  discovery[50] = 0xfc;
  EXPECT_TRUE(check(discovery));
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
  const std::vector<Bytes> seeds = {discoveryData().b, heartbeat(1, 9).b, dataFrag(1, 2, 500, 1200, 1000).b};
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
}  // namespace quad::dds
