// SPDX-License-Identifier: BSD-3-Clause
// The decisions of the datagram fault layer: rates match their probabilities, a seed fixes
// them, only the named sender's datagrams are touched, corruption spares the RTPS header.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "quad/wire/datagram_faults.hpp"

namespace quad::wire {
namespace {

constexpr int kDatagrams = 20000;

std::vector<std::uint8_t> datagramFrom(std::uint8_t sender, std::size_t size = 200)
{
  std::vector<std::uint8_t> d(size, 0);
  d[0] = 'R';
  d[1] = 'T';
  d[2] = 'P';
  d[3] = 'S';
  for (std::size_t i = 8; i < 20; ++i) {
    d[i] = sender;
  }
  return d;
}

DatagramFaults::GuidPrefix prefixOf(std::uint8_t sender)
{
  DatagramFaults::GuidPrefix p;
  p.fill(sender);
  return p;
}

/// Four standard deviations of a binomial fraction: a fixed seed keeps it deterministic,
/// the bound says the generator is not biased.
double bound(double p) { return 4.0 * std::sqrt(p * (1.0 - p) / kDatagrams); }

TEST(DatagramFaults, EachKindHappensAtItsProbability)
{
  for (const auto kind : {DatagramFaultKind::kLoss, DatagramFaultKind::kDuplicate, DatagramFaultKind::kReorder,
                          DatagramFaultKind::kCorrupt}) {
    DatagramFaults faults;
    ASSERT_TRUE(faults.apply({1, kind, 0.2, "", 7}));
    const auto d = datagramFrom(1);
    for (int i = 0; i < kDatagrams; ++i) {
      faults.fate(d.data(), d.size());
    }
    const auto c = faults.counts();
    const std::uint64_t n = kind == DatagramFaultKind::kLoss        ? c.dropped
                            : kind == DatagramFaultKind::kDuplicate ? c.duplicated
                            : kind == DatagramFaultKind::kReorder   ? c.reordered
                                                                    : c.corrupted;
    EXPECT_EQ(c.seen, static_cast<std::uint64_t>(kDatagrams));
    EXPECT_NEAR(static_cast<double>(n) / kDatagrams, 0.2, bound(0.2)) << toString(kind);
  }
}

TEST(DatagramFaults, ASeedFixesEveryDecision)
{
  const auto run = [](std::uint64_t seed) {
    DatagramFaults faults;
    faults.apply({1, DatagramFaultKind::kLoss, 0.3, "", seed});
    faults.apply({2, DatagramFaultKind::kCorrupt, 0.3, "", seed + 1});
    const auto d = datagramFrom(1);
    std::vector<int> decisions;
    for (int i = 0; i < 500; ++i) {
      const auto f = faults.fate(d.data(), d.size());
      decisions.push_back(f.drop ? -1 : f.corrupt ? static_cast<int>(*f.corrupt) * 8 + f.corrupt_bit : 0);
    }
    return decisions;
  };
  EXPECT_EQ(run(11), run(11));
  EXPECT_NE(run(11), run(12));
}

TEST(DatagramFaults, OnlyTheNamedSendersDatagramsAreTouched)
{
  DatagramFaults faults;
  faults.learnSender(prefixOf(1), "mapping");
  faults.learnSender(prefixOf(2), "plant");
  ASSERT_TRUE(faults.apply({1, DatagramFaultKind::kLoss, 1.0, "mapping", 1}));
  const auto mapping = datagramFrom(1);
  const auto plant = datagramFrom(2);
  const auto stranger = datagramFrom(3);
  const std::vector<std::uint8_t> not_rtps(100, 7);
  EXPECT_TRUE(faults.fate(mapping.data(), mapping.size()).drop);
  EXPECT_TRUE(faults.fate(plant.data(), plant.size()).untouched());
  EXPECT_TRUE(faults.fate(stranger.data(), stranger.size()).untouched());
  EXPECT_TRUE(faults.fate(not_rtps.data(), not_rtps.size()).untouched());
  // A fault on every sender reaches datagrams of unknown senders too.
  ASSERT_TRUE(faults.apply({2, DatagramFaultKind::kLoss, 1.0, "", 1}));
  EXPECT_TRUE(faults.fate(not_rtps.data(), not_rtps.size()).drop);
}

TEST(DatagramFaults, CorruptionFlipsOneBitBehindTheRtpsHeader)
{
  DatagramFaults faults;
  ASSERT_TRUE(faults.apply({1, DatagramFaultKind::kCorrupt, 1.0, "", 3}));
  for (const std::size_t size : {21UL, 64UL, 1400UL}) {
    const auto d = datagramFrom(1, size);
    for (int i = 0; i < 200; ++i) {
      const auto f = faults.fate(d.data(), d.size());
      ASSERT_TRUE(f.corrupt);
      EXPECT_GE(*f.corrupt, DatagramFaults::kRtpsHeaderSize);
      EXPECT_LT(*f.corrupt, size);
      EXPECT_GE(f.corrupt_bit, 0);
      EXPECT_LT(f.corrupt_bit, 8);
    }
  }
  // A bare header has nothing behind it to damage.
  const auto header_only = datagramFrom(1, DatagramFaults::kRtpsHeaderSize);
  EXPECT_FALSE(faults.fate(header_only.data(), header_only.size()).corrupt);
}

TEST(DatagramFaults, DelaysAddUpAndALostDatagramIsOnlyLost)
{
  DatagramFaults faults;
  ASSERT_TRUE(faults.apply({1, DatagramFaultKind::kDelay, 0.05, "", 1}));
  ASSERT_TRUE(faults.apply({2, DatagramFaultKind::kReorder, 1.0, "", 1}));
  const auto d = datagramFrom(1);
  const auto f = faults.fate(d.data(), d.size());
  EXPECT_EQ(f.delay_ns, 50'000'000 + DatagramFaults::kReorderHoldNs);
  ASSERT_TRUE(faults.apply({3, DatagramFaultKind::kLoss, 1.0, "", 1}));
  const auto lost = faults.fate(d.data(), d.size());
  EXPECT_TRUE(lost.drop);
  EXPECT_EQ(lost.delay_ns, 0);
  EXPECT_EQ(faults.counts().delayed, 1U);
}

TEST(DatagramFaults, InvalidFaultsAndReusedIdsAreRefusedAndClearingEndsAFault)
{
  DatagramFaults faults;
  EXPECT_FALSE(faults.apply({0, DatagramFaultKind::kLoss, 0.1, "", 1}));
  EXPECT_FALSE(faults.apply({1, DatagramFaultKind::kLoss, 1.5, "", 1}));
  EXPECT_FALSE(faults.apply({1, DatagramFaultKind::kCorrupt, std::nan(""), "", 1}));
  EXPECT_FALSE(faults.apply({1, DatagramFaultKind::kDelay, 11.0, "", 1}));
  EXPECT_NE(DatagramFault({1, DatagramFaultKind::kLoss, -0.1, "", 1}).invalidReason().find("loss -0.1"),
            std::string::npos);
  EXPECT_TRUE(faults.idle());
  ASSERT_TRUE(faults.apply({4, DatagramFaultKind::kLoss, 1.0, "", 1}));
  EXPECT_FALSE(faults.apply({4, DatagramFaultKind::kDelay, 0.1, "", 1}));
  EXPECT_FALSE(faults.idle());
  EXPECT_TRUE(faults.clear(4));
  EXPECT_FALSE(faults.clear(4));
  EXPECT_TRUE(faults.idle());
  EXPECT_TRUE(faults.knows(4));
  const auto d = datagramFrom(1);
  EXPECT_TRUE(faults.fate(d.data(), d.size()).untouched());
}

}  // namespace
}  // namespace quad::wire
