// SPDX-License-Identifier: BSD-3-Clause
// Nodes that share their process's participant (a container): each hears of its own
// endpoints only, the participant lives as long as any of them, and a sample one writes
// reaches another's reader within the process, which, waking on receipt, handles it on the
// writer's thread, with no wake-up of its own, while neither node's work ever runs twice at
// once.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
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
constexpr int kEventsDomain = 68;
constexpr int kPingDomain = 69;

dds::ParticipantOptions options(int domain)
{
  return dds::ParticipantOptions{.name = "shared_test", .domain_id = domain, .transport = dds::Transport::kUdp};
}

bool heardOf(dds::EventQueue& events, dds::EventKind kind, std::string_view topic, std::chrono::milliseconds timeout)
{
  return !events.waitFor([&](const dds::EndpointEvent& e) { return e.kind == kind && e.topic == topic; }, timeout).empty();
}

}  // namespace

TEST(SharedParticipant, EachNodeHearsOfItsOwnEndpointsOnlyAndTheParticipantOutlivesItsMaker)
{
  auto maker = std::make_unique<dds::Participant>(options(kEventsDomain));
  dds::Participant reader_node(maker->shared());
  dds::Participant bystander(maker->shared());
  EXPECT_EQ(maker->raw(), reader_node.raw());  // one DDS participant
  EXPECT_TRUE(maker->reportsProcessInputs());
  EXPECT_FALSE(reader_node.reportsProcessInputs());
  EXPECT_THROW(dds::Participant(std::shared_ptr<dds::SharedParticipant>()), std::invalid_argument);

  auto writer = std::make_unique<dds::Publisher<msg::SimEvent>>(*maker, dds::topics::kSimEvents);
  dds::Subscriber<msg::SimEvent> reader(reader_node, dds::topics::kSimEvents);
  dds::Subscriber<msg::Heartbeat> unrelated(bystander, dds::topics::kHeartbeat);
  const auto topic = dds::topics::kSimEvents.info.name;
  EXPECT_TRUE(heardOf(maker->events(), dds::EventKind::kMatched, topic, std::chrono::seconds(10)));
  EXPECT_TRUE(heardOf(reader_node.events(), dds::EventKind::kMatched, topic, std::chrono::seconds(10)));
  EXPECT_FALSE(heardOf(bystander.events(), dds::EventKind::kMatched, topic, std::chrono::milliseconds(300)));

  msg::SimEvent event;
  event.subject_id(7);
  ASSERT_TRUE(writer->write(event));
  std::optional<msg::SimEvent> got;
  const auto taken = [&] {
    got = reader.take();
    return got.has_value();
  };
  ASSERT_TRUE(test::waitFor(taken));
  EXPECT_EQ(got->subject_id(), 7);

  // The node that made the participant goes; the others keep it.
  writer.reset();
  maker.reset();
  dds::Publisher<msg::SimEvent> second(bystander, dds::topics::kSimEvents);
  event.subject_id(8);
  ASSERT_TRUE(test::waitFor([&] { return second.matchedReaders() == 1; }));
  ASSERT_TRUE(second.write(event));
  ASSERT_TRUE(test::waitFor(taken));
  EXPECT_EQ(got->subject_id(), 8);
}

namespace {

/// One side of a ping-pong within a process: takes `in`, notes which thread took each
/// sample, and answers each on `out` (the pinger sends the next ping, up to `rounds`).
class PingNode : public Node {
public:
  PingNode(std::string name, dds::Participant participant, const dds::Topic<msg::SimEvent>& in, const dds::Topic<msg::SimEvent>& out,
           bool starts, std::int64_t rounds)
      : Node(std::move(name), std::move(participant)),
        in_(this->participant(), in, waker()),
        out_(this->participant(), out),
        starts_(starts),
        rounds_(rounds)
  {
    setWakeOnReceipt(true);
    if (starts) {
      setTickPeriod(10'000'000);
    }
  }

  struct Taken {
    std::int64_t id;
    std::thread::id thread;
  };
  std::vector<Taken> taken() const
  {
    std::lock_guard lock(mutex_);
    return taken_;
  }
  std::thread::id run_thread;
  std::atomic<int> inside{0};  // this node's work running now: never more than one
  std::atomic<bool> overlapped{false};

protected:
  void onStart() override { run_thread = std::this_thread::get_id(); }
  void onTick(std::int64_t) override
  {
    if (starts_ && out_.matchedReaders() > 0 && !started_) {
      started_ = true;
      send(1);
    }
  }
  void onWake() override
  {
    overlapped = overlapped || ++inside > 1;
    while (auto e = in_.take()) {
      {
        std::lock_guard lock(mutex_);
        taken_.push_back({e->subject_id(), std::this_thread::get_id()});
      }
      const std::int64_t next = starts_ ? e->subject_id() + 1 : e->subject_id();
      if (next <= rounds_) {
        send(next);
      }
    }
    --inside;
  }

private:
  void send(std::int64_t id)
  {
    msg::SimEvent e;
    e.subject_id(id);
    EXPECT_TRUE(out_.write(e));
  }

  dds::Subscriber<msg::SimEvent> in_;
  dds::Publisher<msg::SimEvent> out_;
  bool starts_;
  bool started_ = false;
  std::int64_t rounds_;
  mutable std::mutex mutex_;
  std::vector<Taken> taken_;
};

}  // namespace

TEST(SharedParticipant, NodesOfOneProcessPassSamplesOnTheWritersThreadEachInOrderAndOnce)
{
  constexpr std::int64_t kRounds = 50;
  dds::Participant maker(options(kPingDomain));
  const auto shared = maker.shared();
  PingNode ping("ping", std::move(maker), dds::topics::kSimEvents, dds::topics::kFaultEvents, true, kRounds);
  PingNode pong("pong", dds::Participant(shared), dds::topics::kFaultEvents, dds::topics::kSimEvents, false, kRounds);
  std::thread ping_thread([&] { ping.run(); });
  std::thread pong_thread([&] { pong.run(); });
  const bool done = test::waitFor([&] { return ping.taken().size() >= static_cast<std::size_t>(kRounds); });
  ping.stop();
  pong.stop();
  ping_thread.join();
  pong_thread.join();
  ASSERT_TRUE(done) << ping.taken().size() << " of " << kRounds << " rounds";

  std::vector<std::int64_t> pings;
  std::vector<std::int64_t> pongs;
  std::vector<std::int64_t> expected;
  std::size_t on_pingers_thread = 0;
  for (const auto& t : pong.taken()) {
    pings.push_back(t.id);
    on_pingers_thread += t.thread == ping.run_thread ? 1U : 0U;
  }
  for (const auto& t : ping.taken()) {
    pongs.push_back(t.id);
  }
  for (std::int64_t i = 1; i <= kRounds; ++i) {
    expected.push_back(i);
  }
  EXPECT_EQ(pings, expected);
  EXPECT_EQ(pongs, expected);
  // The pinger writes from its own thread (its tick, then its onWake): the ponger, waiting,
  // takes each ping there and then, without being woken.
  EXPECT_GE(on_pingers_thread, static_cast<std::size_t>(kRounds) * 9 / 10) << "of " << kRounds;
  EXPECT_FALSE(ping.overlapped.load());
  EXPECT_FALSE(pong.overlapped.load());
}

}  // namespace quad::runtime
