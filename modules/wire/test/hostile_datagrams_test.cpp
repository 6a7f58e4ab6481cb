// SPDX-License-Identifier: BSD-3-Clause
// The validating transport between real participants over UDP: every regression datagram
// (tests/fixtures/datagrams) sent to their ports is dropped or harmless, and they keep
// talking; the traffic of a real exchange, fragments included, passes untouched.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <thread>
#include <vector>

#include "quad/common/time.hpp"
#include "wait.hpp"
#include "quad/dds/liveliness.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/wire/rtps_check.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/wire/validating_transport.hpp"
#include "datagram_mutator.hpp"

namespace quad::wire {
namespace {

using dds::Participant;
using dds::ParticipantOptions;
using dds::Publisher;
using dds::Subscriber;
using dds::Transport;
namespace topics = dds::topics;

// ctest runs each case alone and in parallel with others: each has a domain of its own.
constexpr int kHostileDomain = 171;
constexpr int kCleanDomain = 172;
constexpr int kFuzzedDomain = 166;

/// The listener has a fault layer (with no fault in it): that turns this process's
/// intraprocess delivery off, so that the samples cross UDP and the validating layer in
/// front of it, as they do between processes.
ParticipantOptions options(const std::string& name, int domain)
{
  return ParticipantOptions{.name = name, .domain_id = domain, .transport = Transport::kUdp,
                            .fault_layer = name == "listener", .udp_max_message = 1400};
}

/// A talker and a listener on one domain with the events topic between them.
struct Talk {
  explicit Talk(int domain)
      : talker(options("talker", domain)),
        listener(options("listener", domain)),
        writer(talker, topics::kSimEvents),
        reader(listener, topics::kSimEvents)
  {
  }
  bool matched()
  {
    return test::waitFor([&] { return reader.matchedWriters() == 1 && writer.matchedReaders() == 1; });
  }
  /// Sends `count` events and says how many arrived.
  int exchange(int count)
  {
    int got = 0;
    for (int i = 0; i < count; ++i) {
      msg::SimEvent e;
      e.subject_id(i);
      writer.write(e);
    }
    test::waitFor([&] {
      got += static_cast<int>(reader.takeAll().size());
      return got >= count;
    });
    return got;
  }

  Participant talker;
  Participant listener;
  Publisher<msg::SimEvent> writer;
  Subscriber<msg::SimEvent> reader;
};

std::vector<std::vector<std::uint8_t>> regressionDatagrams()
{
  std::vector<std::vector<std::uint8_t>> all;
  for (const auto& entry : std::filesystem::directory_iterator(QUAD_DATAGRAMS_DIR)) {
    if (entry.path().extension() == ".bin") {
      std::ifstream in(entry.path(), std::ios::binary);
      all.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  return all;
}

TEST(HostileDatagrams, NoneEndsAParticipantAndTalkGoesOn)
{
  Talk talk(kHostileDomain);
  ASSERT_TRUE(talk.matched());
  ASSERT_EQ(talk.exchange(20), 20);

  const auto datagrams = regressionDatagrams();
  ASSERT_GE(datagrams.size(), 10u);
  std::size_t malformed_files = 0;
  for (const auto& d : datagrams) {
    malformed_files += checkRtpsDatagram(d.data(), d.size()) ? 1U : 0U;
  }
  const std::uint64_t before = malformedDatagrams().count;
  // The unicast metatraffic and user ports of participant ids 0..3 (RTPS port mapping: 7400 +
  // 250 * domain + 10 / 11 + 2 * id): both participants listen on some of them.
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  int sent_ports = 0;
  for (int id = 0; id < 4; ++id) {
    for (int offset : {10, 11}) {
      sockaddr_in to{};
      to.sin_family = AF_INET;
      to.sin_port = htons(static_cast<std::uint16_t>(7400 + 250 * kHostileDomain + offset + 2 * id));
      to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      for (int round = 0; round < 3; ++round) {
        for (const auto& d : datagrams) {
          ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to));
        }
      }
      ++sent_ports;
    }
  }
  ::close(fd);
  // Two participants listen on two unicast ports each: three rounds of every malformed file.
  EXPECT_TRUE(test::waitFor([&] { return malformedDatagrams().count - before >= 3 * 4 * malformed_files; }))
      << "dropped " << malformedDatagrams().count - before << " of " << 3 * 4 * malformed_files << " malformed";
  EXPECT_FALSE(malformedDatagrams().last.empty());
  // Still alive (a crash would have ended this process), still matched, still talking.
  EXPECT_EQ(talk.exchange(50), 50);
  EXPECT_EQ(talk.reader.matchedWriters(), 1);
  EXPECT_EQ(sent_ports, 8);
}

TEST(HostileDatagrams, TheMutatorStartsFromWellFormedDatagramsAndBreaksMany)
{
  fuzz::DatagramMutator mutator(3);
  for (std::size_t i = 0; i < mutator.templates(); ++i) {
    const auto& t = mutator.templateBytes(i);
    const auto defect = checkRtpsDatagram(t.data(), t.size());
    EXPECT_FALSE(defect) << "template " << i << ": " << defect->what;
  }
  int refused = 0;
  for (int i = 0; i < 10000; ++i) {
    const auto d = mutator.next();
    refused += checkRtpsDatagram(d.data(), d.size()) ? 1 : 0;
  }
  EXPECT_GT(refused, 3000);  // most break a structure the check knows...
  EXPECT_LT(refused, 9500);  // ...and some reach Fast DDS's parser
}

TEST(HostileDatagrams, TwoHundredThousandFuzzedDatagramsEndNoParticipant)
{
  Talk talk(kFuzzedDomain);
  ASSERT_TRUE(talk.matched());
  const MalformedDatagrams before = malformedDatagrams();
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  fuzz::DatagramMutator mutator(11);
  for (int i = 0; i < 200'000; ++i) {
    const auto d = mutator.next();
    sockaddr_in to{};
    to.sin_family = AF_INET;
    // Both participants' unicast metatraffic and user ports (ids 0 and 1).
    to.sin_port = htons(static_cast<std::uint16_t>(7400 + 250 * kFuzzedDomain + 10 + (i % 4)));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to));
    if (i % 1000 == 999) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));  // let the receivers keep up
    }
  }
  ::close(fd);
  const MalformedDatagrams after = malformedDatagrams();
  std::cout << "checked " << after.checked - before.checked << " datagrams, dropped "
            << after.count - before.count << " as malformed\n";
  EXPECT_GT(after.checked - before.checked, 100'000u);  // most reached the participants
  EXPECT_EQ(talk.exchange(50), 50);  // alive and talking
  EXPECT_EQ(talk.reader.matchedWriters(), 1);
}

TEST(HostileDatagrams, RealTrafficPassesTheCheckWhole)
{
  // Discovery, events, a 300 kB map snapshot in 1400-byte fragments and liveliness:
  // nothing dropped.
  const MalformedDatagrams before = malformedDatagrams();
  Talk talk(kCleanDomain);
  Publisher<msg::MapSnapshot> snapshots_out(talk.talker, topics::kMapSnapshot);
  Subscriber<msg::MapSnapshot> snapshots_in(talk.listener, topics::kMapSnapshot);
  ASSERT_TRUE(talk.matched());
  ASSERT_TRUE(test::waitFor([&] { return snapshots_in.matchedWriters() == 1; }));
  EXPECT_EQ(talk.exchange(100), 100);
  msg::MapSnapshot snapshot;
  snapshot.resolution(0.2);
  snapshot.octree().resize(300'000);
  for (std::size_t i = 0; i < snapshot.octree().size(); ++i) {
    snapshot.octree()[i] = static_cast<std::uint8_t>(i * 7);
  }
  ASSERT_TRUE(snapshots_out.write(snapshot));
  std::optional<msg::MapSnapshot> got;
  EXPECT_TRUE(test::waitFor([&] {
    if (auto s = snapshots_in.take()) {
      got = std::move(s);
    }
    return got.has_value();
  }));
  ASSERT_TRUE(got);
  EXPECT_EQ(got->octree(), snapshot.octree());
  // Liveliness assertions for 1.5 s: a module's heartbeat writer's (MANUAL_BY_TOPIC, 0.5 s
  // lease), asserted by its keeper every 125 ms between the beats.
  Publisher<msg::Heartbeat> beats_out(talk.talker, topics::kHeartbeat);
  Subscriber<msg::Heartbeat> beats_in(talk.listener, topics::kHeartbeat);
  // Both ways: a beat written before the writer matched the reader (volatile) never reaches it.
  ASSERT_TRUE(test::waitFor([&] { return beats_in.matchedWriters() == 1 && beats_out.matchedReaders() == 1; }));
  int beats = 0;
  {
    dds::LivelinessKeeper alive(beats_out);
    for (int i = 1; i <= 3; ++i) {
      msg::Heartbeat beat;
      beat.header().seq(static_cast<std::uint32_t>(i));
      beats_out.write(beat);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      beats += static_cast<int>(beats_in.takeAll().size());
    }
  }
  EXPECT_TRUE(test::waitFor([&] {
    beats += static_cast<int>(beats_in.takeAll().size());
    return beats == 3;
  }));
  const MalformedDatagrams m = malformedDatagrams();
  EXPECT_EQ(m.count, before.count) << m.last;
  EXPECT_GT(m.checked - before.checked, 200u);  // every datagram went through the check
}

}  // namespace
}  // namespace quad::wire
