// SPDX-License-Identifier: BSD-3-Clause
// A node that handles arriving samples on the thread that received them (wake-on-receipt):
// while its own thread waits, onWake() runs on the receiving thread; while its own thread is
// busy, a sample waits for it and is taken by it afterwards; either way every sample is taken
// once, in order. Without wake-on-receipt, onWake() runs on the node's thread only.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "wait.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/node.hpp"

namespace quad::runtime {
namespace {

// ctest runs each case alone and in parallel with others: each has a domain of its own.
constexpr int kReceiptDomain = 104;
constexpr int kBusyDomain = 105;
constexpr int kLoopDomain = 97;

dds::ParticipantOptions options(const std::string& name, int domain)
{
  return dds::ParticipantOptions{.name = name, .domain_id = domain, .transport = dds::Transport::kUdp};
}

/// Takes quad/sim/events and notes, for each sample, whether run()'s thread took it.
class EventNode : public Node {
public:
  EventNode(int domain, bool wake_on_receipt, std::int64_t busy_tick_ns = 0)
      : Node("wake_test_node", options("wake_test_node", domain)), events_(participant(), dds::topics::kSimEvents, waker())
  {
    setWakeOnReceipt(wake_on_receipt);
    if (busy_tick_ns > 0) {
      setTickPeriod(busy_tick_ns);
    }
  }

  struct Taken {
    std::int64_t id;
    bool on_run_thread;
  };
  std::vector<Taken> taken() const
  {
    std::lock_guard lock(mutex_);
    return taken_;
  }
  std::thread::id run_thread;
  std::atomic<bool> busy{false};     // onTick is holding the node
  std::atomic<bool> release{false};  // lets the busy onTick return

protected:
  void onStart() override { run_thread = std::this_thread::get_id(); }
  void onWake() override
  {
    while (auto e = events_.take()) {
      std::lock_guard lock(mutex_);
      taken_.push_back({e->subject_id(), std::this_thread::get_id() == run_thread});
    }
  }
  void onTick(std::int64_t) override
  {
    if (release) {
      return;
    }
    busy = true;  // once: busy until the test releases it
    test::waitFor([&] { return release.load(); });
    busy = false;
  }

private:
  dds::Subscriber<msg::SimEvent> events_;
  mutable std::mutex mutex_;
  std::vector<Taken> taken_;
};

struct Talker {
  explicit Talker(int domain) : participant(options("wake_test_talker", domain)), writer(participant, dds::topics::kSimEvents) {}
  void send(std::int64_t id)
  {
    msg::SimEvent e;
    e.subject_id(id);
    EXPECT_TRUE(writer.write(e));
  }
  dds::Participant participant;
  dds::Publisher<msg::SimEvent> writer;
};

std::vector<std::int64_t> ids(const std::vector<EventNode::Taken>& taken)
{
  std::vector<std::int64_t> out;
  for (const auto& t : taken) {
    out.push_back(t.id);
  }
  return out;
}

std::vector<std::int64_t> oneTo(std::int64_t n)
{
  std::vector<std::int64_t> out;
  for (std::int64_t i = 1; i <= n; ++i) {
    out.push_back(i);
  }
  return out;
}

/// Runs a node, sends it `n` samples 5 ms apart (its thread back to waiting between them),
/// and once it took them all, stops it: what it took.
std::vector<EventNode::Taken> sendSpaced(int domain, bool wake_on_receipt, int n)
{
  EventNode node(domain, wake_on_receipt);
  std::thread running([&] { node.run(); });
  Talker talker(domain);
  EXPECT_TRUE(test::waitFor([&] { return talker.writer.matchedReaders() == 1; }));
  for (int i = 1; i <= n; ++i) {
    talker.send(i);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(test::waitFor([&] { return node.taken().size() >= static_cast<std::size_t>(n); }));
  node.stop();
  running.join();
  return node.taken();
}

}  // namespace

TEST(NodeWake, SamplesAreTakenOnTheReceivingThreadWhileTheNodeWaitsEachOnceInOrder)
{
  constexpr int kSamples = 40;
  const auto taken = sendSpaced(kReceiptDomain, true, kSamples);
  EXPECT_EQ(ids(taken), oneTo(kSamples));
  std::size_t elsewhere = 0;
  for (const auto& t : taken) {
    elsewhere += t.on_run_thread ? 0U : 1U;
  }
  // The node's thread takes a sample only when it was at work as it came (a heartbeat).
  EXPECT_GE(elsewhere, kSamples / 2) << "of " << kSamples;
}

TEST(NodeWake, ASampleThatComesWhileTheNodeIsBusyWaitsForItsThreadAndIsNotLost)
{
  constexpr int kSamples = 10;
  EventNode node(kBusyDomain, true, 20'000'000);
  std::thread running([&] { node.run(); });
  Talker talker(kBusyDomain);
  ASSERT_TRUE(test::waitFor([&] { return talker.writer.matchedReaders() == 1; }));
  ASSERT_TRUE(test::waitFor([&] { return node.busy.load(); }));
  for (int i = 1; i <= kSamples; ++i) {
    talker.send(i);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_TRUE(node.taken().empty());  // the node is busy: nothing runs beside it
  node.release = true;
  ASSERT_TRUE(test::waitFor([&] { return node.taken().size() >= kSamples; }));
  node.stop();
  running.join();
  const auto taken = node.taken();
  EXPECT_EQ(ids(taken), oneTo(kSamples));
  EXPECT_TRUE(taken.front().on_run_thread);  // woken as it came, the node's thread took them
}

TEST(NodeWake, WithoutWakeOnReceiptEverySampleIsTakenOnTheNodesThread)
{
  constexpr int kSamples = 10;
  const auto taken = sendSpaced(kLoopDomain, false, kSamples);
  EXPECT_EQ(ids(taken), oneTo(kSamples));
  for (const auto& t : taken) {
    EXPECT_TRUE(t.on_run_thread) << "sample " << t.id;
  }
}

}  // namespace quad::runtime
