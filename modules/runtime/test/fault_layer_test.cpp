// SPDX-License-Identifier: BSD-3-Clause
// The datagram fault layer between real participants over UDP: reliable topics come through
// loss, duplication, reordering and delay whole and in order; a node applies, refuses and
// clears faults commanded on quad/system/fault and acknowledges each.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "quad/common/time.hpp"
#include "wait.hpp"
#include "quad/dds/fault_messages.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/node.hpp"

namespace quad::runtime {
namespace {

// ctest runs each case alone and in parallel with others: each has a domain of its own.
constexpr int kLossDomain = 159;
constexpr int kReorderDomain = 197;
constexpr int kNodeDomain = 198;
constexpr int kSamples = 200;

dds::ParticipantOptions options(const std::string& name, bool fault_layer, int domain)
{
  return dds::ParticipantOptions{.name = name, .domain_id = domain, .transport = dds::Transport::kUdp,
                            .fault_layer = fault_layer};
}

/// Sends kSamples events from "talker" to a faulty "listener" and returns their ids in the
/// order they were taken.
std::vector<std::int64_t> sendThrough(int domain, const std::vector<wire::DatagramFault>& faults,
                                      wire::DatagramFaults::Counts* counts)
{
  dds::Participant talker(options("talker", false, domain));
  dds::Participant listener(options("listener", true, domain));
  dds::Publisher<msg::SimEvent> writer(talker, dds::topics::kSimEvents);
  dds::Subscriber<msg::SimEvent> reader(listener, dds::topics::kSimEvents);
  EXPECT_TRUE(test::waitFor([&] { return reader.matchedWriters() == 1 && writer.matchedReaders() == 1; }));
  for (const auto& f : faults) {
    EXPECT_TRUE(listener.datagramFaults()->apply(f));
  }
  std::vector<std::int64_t> got;
  for (int i = 1; i <= kSamples; ++i) {
    msg::SimEvent e;
    e.subject_id(i);
    EXPECT_TRUE(writer.write(e));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    for (const auto& s : reader.takeAll()) {
      got.push_back(s.subject_id());
    }
  }
  test::waitFor([&] {
    for (const auto& s : reader.takeAll()) {
      got.push_back(s.subject_id());
    }
    return got.size() >= static_cast<std::size_t>(kSamples);
  });
  *counts = listener.datagramFaults()->counts();
  return got;
}

std::vector<std::int64_t> oneToN()
{
  std::vector<std::int64_t> ids;
  for (int i = 1; i <= kSamples; ++i) {
    ids.push_back(i);
  }
  return ids;
}

TEST(FaultLayer, AReliableTopicComesThroughThirtyPercentLossWholeAndInOrder)
{
  wire::DatagramFaults::Counts counts;
  const auto got = sendThrough(kLossDomain, {{1, wire::DatagramFaultKind::kLoss, 0.3, "talker", 5}}, &counts);
  EXPECT_EQ(got, oneToN());
  // Every sample crossed the layer (nothing went around it through memory), and it dropped
  // about 30 % of the datagrams: the topic repaired that.
  EXPECT_GE(counts.seen, static_cast<std::uint64_t>(kSamples));
  EXPECT_GT(counts.dropped, counts.seen / 5);
}

TEST(FaultLayer, DuplicatedReorderedAndDelayedDatagramsDeliverEachSampleOnceInOrder)
{
  wire::DatagramFaults::Counts counts;
  const auto got = sendThrough(kReorderDomain,
                               {{1, wire::DatagramFaultKind::kDuplicate, 0.3, "talker", 5},
                                {2, wire::DatagramFaultKind::kReorder, 0.3, "talker", 6},
                                {3, wire::DatagramFaultKind::kDelay, 0.005, "talker", 7}},
                               &counts);
  EXPECT_EQ(got, oneToN());
  EXPECT_GE(counts.seen, static_cast<std::uint64_t>(kSamples));
  EXPECT_GT(counts.duplicated, 0U);
  EXPECT_GT(counts.reordered, 0U);
  EXPECT_GT(counts.delayed, counts.reordered);
}

class IdleNode : public Node {
public:
  IdleNode() : Node("layer_test_node", options("layer_test_node", true, kNodeDomain)) {}
};

TEST(FaultLayer, ANodeAppliesRefusesAndClearsCommandedFaultsAndAcknowledgesEach)
{
  IdleNode node;
  std::thread running([&] { node.run(); });
  dds::Participant tool(options("layer_test_tool", false, kNodeDomain));
  dds::Publisher<msg::FaultCommand> commands(tool, dds::topics::kFault);
  dds::Subscriber<msg::SimEvent> acks(tool, dds::topics::kFaultEvents);
  ASSERT_TRUE(test::waitFor([&] { return commands.matchedReaders() == 1 && acks.matchedWriters() == 1; }));

  const auto send = [&](msg::FaultCommand c) {
    c.header().stamp_ns(12'000'000'000);
    EXPECT_TRUE(commands.write(c));
  };
  const auto nextAck = [&] {
    std::optional<msg::SimEvent> e;
    test::waitFor([&] { return (e = acks.take()).has_value(); });
    return e;
  };
  send(dds::toCommand({41, wire::DatagramFaultKind::kLoss, 0.5, "elsewhere", 3}, "layer_test_node"));
  send(dds::toCommand({42, wire::DatagramFaultKind::kLoss, 0.5, "", 3}, "another_module"));  // not this node's
  auto ack = nextAck();
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->kind(), msg::SIM_EVENT_FAULT_APPLIED);
  EXPECT_EQ(ack->subject_id(), 41);
  EXPECT_EQ(ack->header().stamp_ns(), 12'000'000'000);
  EXPECT_NE(ack->detail().to_string().find("loss 0.5 of datagrams from elsewhere"), std::string::npos);
  EXPECT_TRUE(node.isDatagramFaultId(41));
  EXPECT_FALSE(node.isDatagramFaultId(42));

  msg::FaultCommand bad = dds::toCommand({43, wire::DatagramFaultKind::kCorrupt, 2.0, "", 3}, "layer_test_node");
  send(bad);
  ack = nextAck();
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->kind(), msg::SIM_EVENT_FAULT_REJECTED);
  EXPECT_NE(ack->detail().to_string().find("corrupt 2: expected a probability in [0, 1]"), std::string::npos)
      << ack->detail().to_string();

  msg::FaultCommand clear;
  clear.kind(msg::FAULT_CLEAR);
  clear.fault_id(41);
  clear.module_name("layer_test_node");
  send(clear);
  ack = nextAck();
  ASSERT_TRUE(ack);
  EXPECT_EQ(ack->kind(), msg::SIM_EVENT_FAULT_CLEARED);
  EXPECT_EQ(ack->subject_id(), 41);
  EXPECT_TRUE(node.participant().datagramFaults()->idle());

  node.stop();
  running.join();
}

TEST(FaultLayer, SharedMemoryAndAFaultLayerAreRefusedTogether)
{
  dds::ParticipantOptions o = options("layer_test_shm", true, kNodeDomain);
  o.transport = dds::Transport::kSharedMemory;
  EXPECT_THROW(dds::Participant p(o), std::invalid_argument);
}

}  // namespace
}  // namespace quad::runtime
