// SPDX-License-Identifier: BSD-3-Clause
// MCAP writing and reading: round trips, the layout the specification fixes, and bad files.
#include "quad/bag/mcap.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "scratch.hpp"

namespace quad::bag {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> bytesOf(const fs::path& p)
{
  const std::string s = quad::test::readFile(p);
  return {s.begin(), s.end()};
}

void writeBytes(const fs::path& p, const std::vector<std::uint8_t>& b)
{
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// Two channels, 1000 messages of varied sizes, small chunks so that there are many.
fs::path writeSample(const fs::path& dir, const std::string& compression = "")
{
  const fs::path file = dir / ("sample" + compression + ".mcap");
  McapWriter w(file, 4096, compression);
  const auto schema = w.addSchema("quad::msg::Thing", "omgidl", "module quad { module msg { struct Thing { long x; }; }; };");
  const auto a = w.addChannel(schema, "quad/a", "cdr", {{"qos", "state"}});
  const auto b = w.addChannel(schema, "quad/b", "cdr", {});
  for (std::uint32_t i = 0; i < 1000; ++i) {
    std::vector<std::uint8_t> payload(4 + i % 97, static_cast<std::uint8_t>(i));
    w.write(i % 3 == 0 ? b : a, i, 1'000'000'000ULL + i * 1000ULL, 999'000'000ULL + i * 1000ULL, payload.data(),
            payload.size());
  }
  w.addMetadata("run", {{"manifest", "demo.yaml"}});
  w.close();
  return file;
}

TEST(Mcap, Crc32MatchesTheStandardCheckValue)
{
  EXPECT_EQ(crc32("123456789", 9), 0xCBF43926U);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(crc32("", 0), 0U);
  // Continuing a CRC gives the CRC of the concatenation.
  EXPECT_EQ(crc32("56789", 5, crc32("1234", 4)), 0xCBF43926U);
  // Folded by carry-less multiplication (where the CPU has it) and eight bytes at a time
  // through tables, it is what the bitwise definition gives, at every length and alignment,
  // whole or continued.
  const auto bitwise = [](const std::uint8_t* p, std::size_t n) {
    std::uint32_t c = 0xFFFFFFFFU;
    for (std::size_t i = 0; i < n; ++i) {
      c ^= p[i];
      for (int k = 0; k < 8; ++k) {
        c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
      }
    }
    return ~c;
  };
  std::mt19937 rng(11);
  std::vector<std::uint8_t> bytes(1500);
  for (auto& b : bytes) {
    b = static_cast<std::uint8_t>(rng());
  }
  for (const auto& crc : {&crc32, &crc32Tables}) {
    for (std::size_t offset = 0; offset < 16; ++offset) {
      for (std::size_t n = 0; n + offset <= bytes.size(); n += 1 + n / 16) {
        const std::uint8_t* p = bytes.data() + offset;
        ASSERT_EQ(crc(p, n, 0), bitwise(p, n)) << "offset " << offset << " length " << n;
        ASSERT_EQ(crc(p + n / 3, n - n / 3, crc(p, n / 3, 0)), bitwise(p, n)) << "split at " << n / 3;
      }
    }
  }
}

TEST(Mcap, WhatIsWrittenIsReadBackInOrder)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_roundtrip");
  const auto contents = readMcap(writeSample(dir));
  EXPECT_TRUE(contents.complete);
  ASSERT_EQ(contents.schemas.size(), 1U);
  EXPECT_EQ(contents.schemas[0].id, 1);  // 0 means "no schema"
  EXPECT_EQ(contents.schemas[0].encoding, "omgidl");
  ASSERT_EQ(contents.channels.size(), 2U);
  EXPECT_EQ(contents.channels[0].metadata.at("qos"), "state");
  ASSERT_EQ(contents.messages.size(), 1000U);
  EXPECT_GT(contents.chunks, 10U);
  for (std::uint32_t i = 0; i < 1000; ++i) {
    const auto& m = contents.messages[i];
    EXPECT_EQ(m.sequence, i);
    EXPECT_EQ(m.channel_id, i % 3 == 0 ? 1 : 0);
    EXPECT_EQ(m.log_time, 1'000'000'000ULL + i * 1000ULL);
    EXPECT_EQ(m.publish_time, 999'000'000ULL + i * 1000ULL);
    ASSERT_EQ(m.data.size(), 4 + i % 97);
    EXPECT_EQ(m.data.front(), static_cast<std::uint8_t>(i));
  }
  ASSERT_EQ(contents.metadata.size(), 1U);
  EXPECT_EQ(contents.metadata[0].values.at("manifest"), "demo.yaml");
  fs::remove_all(dir);
}

TEST(Mcap, ZstdChunksReadBackTheSameAndAreSmaller)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_zstd");
  const auto plain = readMcap(writeSample(dir));
  const fs::path packed_file = writeSample(dir, "zstd");
  const auto packed = readMcap(packed_file);
  ASSERT_EQ(packed.messages.size(), plain.messages.size());
  for (std::size_t i = 0; i < plain.messages.size(); ++i) {
    EXPECT_EQ(packed.messages[i].data, plain.messages[i].data);
  }
  EXPECT_LT(fs::file_size(packed_file), fs::file_size(dir / "sample.mcap") / 2);  // repetitive payloads
  EXPECT_THROW(McapWriter(dir / "x.mcap", 4096, "brotli"), BagError);
  fs::remove_all(dir);
}

TEST(Mcap, AZstdChunkClaimingMoreThanItHoldsIsRefusedWithoutAllocatingTheClaim)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_claims");
  const auto good = bytesOf(writeSample(dir, "zstd"));
  // The first chunk record: records are opcode, u64 length, body, from byte 8 on.
  std::size_t chunk = 8;
  while (good.at(chunk) != 0x06) {
    std::uint64_t length = 0;
    for (int i = 0; i < 8; ++i) {
      length |= static_cast<std::uint64_t>(good.at(chunk + 1 + static_cast<std::size_t>(i))) << (8 * i);
    }
    chunk += 9 + length;
  }
  const std::size_t claim = chunk + 9 + 16;  // after the start and end times
  const auto claiming = [&](std::uint64_t bytes) {
    auto b = good;
    for (int i = 0; i < 8; ++i) {
      b[claim + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(bytes >> (8 * i));
    }
    try {
      readMcap(b, "claims.mcap");
    } catch (const BagError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  // 900 MB claimed for a few KiB of data: refused once the data runs out, not allocated first.
  EXPECT_NE(claiming(900'000'000).find("claims.mcap: at byte"), std::string::npos);
  EXPECT_NE(claiming(900'000'000).find("not the 900000000 it claims"), std::string::npos) << claiming(900'000'000);
  EXPECT_NE(claiming(std::uint64_t{1} << 40).find("more than any chunk holds"), std::string::npos);
  EXPECT_NE(claiming(10).find("more than the 10 bytes it claims"), std::string::npos) << claiming(10);
  EXPECT_EQ(readMcap(good, "good.mcap").messages.size(), 1000U);
  fs::remove_all(dir);
}

TEST(Mcap, TheFileHasTheLayoutTheSpecificationFixes)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_layout");
  const auto b = bytesOf(writeSample(dir));
  const std::string magic("\x89MCAP0\r\n", 8);
  ASSERT_GT(b.size(), 100U);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 8), magic);
  EXPECT_EQ(std::string(b.end() - 8, b.end()), magic);
  EXPECT_EQ(b[8], 0x01);  // the Header record first
  // The footer: opcode 0x02, length 20, then summary start, summary offset start, CRC.
  const std::size_t footer = b.size() - 8 - 29;
  EXPECT_EQ(b[footer], 0x02);
  auto u64 = [&](std::size_t at) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) {
      v |= static_cast<std::uint64_t>(b[at + static_cast<std::size_t>(i)]) << (8 * i);
    }
    return v;
  };
  EXPECT_EQ(u64(footer + 1), 20U);
  const std::uint64_t summary_start = u64(footer + 9);
  const std::uint64_t offsets_start = u64(footer + 17);
  ASSERT_GT(summary_start, 8U);
  ASSERT_GT(offsets_start, summary_start);
  EXPECT_EQ(b[summary_start], 0x03);  // the summary starts with the schemas
  EXPECT_EQ(b[offsets_start], 0x0E);  // then come summary offset records
  // The summary CRC covers the summary section up to the CRC field of the footer.
  std::uint32_t crc = 0;
  for (int i = 0; i < 4; ++i) {
    crc |= static_cast<std::uint32_t>(b[footer + 25 + static_cast<std::size_t>(i)]) << (8 * i);
  }
  EXPECT_EQ(crc, crc32(b.data() + summary_start, footer + 25 - summary_start));
  fs::remove_all(dir);
}

TEST(Mcap, ACorruptChunkIsReportedWithItsOffset)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_corrupt");
  const fs::path file = writeSample(dir);
  auto b = bytesOf(file);
  b[1000] ^= 0xFFU;  // inside the first chunk's records (the records before it take ~230 bytes)
  writeBytes(file, b);
  try {
    readMcap(file);
    FAIL() << "a corrupt chunk was read";
  } catch (const BagError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string() + ": at byte "), std::string::npos) << what;
    EXPECT_NE(what.find("CRC mismatch"), std::string::npos) << what;
  }
  fs::remove_all(dir);
}

TEST(Mcap, ATruncatedFileIsAnErrorAndTolerantReadingKeepsTheCompleteChunks)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_truncated");
  const fs::path file = writeSample(dir);
  const auto whole = readMcap(file);
  auto b = bytesOf(file);
  b.resize(b.size() / 2);  // as if the writer was killed half way
  writeBytes(file, b);
  EXPECT_THROW(readMcap(file), BagError);
  const auto partial = readMcap(file, true);
  EXPECT_FALSE(partial.complete);
  EXPECT_FALSE(partial.problem.empty());
  EXPECT_GT(partial.messages.size(), 300U);
  EXPECT_LT(partial.messages.size(), 1000U);
  for (std::size_t i = 0; i < partial.messages.size(); ++i) {
    EXPECT_EQ(partial.messages[i].sequence, whole.messages[i].sequence);
  }
  fs::remove_all(dir);
}

TEST(Mcap, RecoverRewritesACutFileWholeWithEveryCompleteChunk)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_recover");
  const fs::path file = writeSample(dir);
  auto b = bytesOf(file);
  b.resize(b.size() * 2 / 3);
  writeBytes(file, b);
  const auto read = recoverMcap(file, dir / "recovered.mcap");
  EXPECT_FALSE(read.problem.empty());
  const auto whole = readMcap(dir / "recovered.mcap");  // strict: it is a whole file now
  EXPECT_TRUE(whole.complete);
  ASSERT_EQ(whole.messages.size(), read.messages.size());
  EXPECT_GT(whole.messages.size(), 500U);
  for (std::size_t i = 0; i < whole.messages.size(); ++i) {
    EXPECT_EQ(whole.messages[i].sequence, i);
    EXPECT_EQ(whole.messages[i].data, read.messages[i].data);
  }
  EXPECT_EQ(whole.channels.size(), 2U);
  fs::remove_all(dir);
}

TEST(Mcap, WrongMagicAndMissingFilesAreClearErrors)
{
  const fs::path dir = quad::test::scratchDir("quad_mcap_magic");
  std::ofstream(dir / "not.mcap") << "this is not a recording";
  try {
    readMcap(dir / "not.mcap");
    FAIL();
  } catch (const BagError& e) {
    EXPECT_NE(std::string(e.what()).find("not an MCAP file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readMcap(dir / "missing.mcap"), BagError);
  EXPECT_THROW(McapWriter(dir / "no/such/folder/x.mcap"), BagError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quad::bag
