// SPDX-License-Identifier: BSD-3-Clause
// A test participant for multi-process tests of quad::dds. Domain and transport come from
// the environment (QUAD_DOMAIN_ID, QUAD_TRANSPORT), as for every quad process.
//
//   dds_probe send-commands N            write N VehicleCommands once a reader matched
//   dds_probe receive-commands N MS      expect N commands, in order, within MS milliseconds
//   dds_probe send-state MS              write VehicleState at 100 Hz for MS milliseconds
//   dds_probe receive-state-reliable MS  read quad/sim/state asking for RELIABLE (the contract
//                                        says BEST_EFFORT) and print the incompatibility
//   dds_probe send-heartbeat-as-state MS write Heartbeats on the quad/sim/state topic name
//   dds_probe receive-state MS           read quad/sim/state; print type mismatches seen
//   dds_probe lockstep-clock STEPS MS NAME...  step sim time 1 ms at a time, waiting up to MS
//                                        at each step for every NAME to report done
//   dds_probe lockstep-participant NAME  report done up to each sim clock tick received
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/lockstep.hpp"
#include "wait.hpp"

namespace {

using namespace std::chrono_literals;
using quad::dds::EventKind;
using quad::dds::EndpointEvent;
using quad::dds::Participant;
namespace topics = quad::dds::topics;

int sendCommands(Participant& p, int count)
{
  quad::dds::Publisher<quad::msg::VehicleCommand> pub(p, topics::kVehicleCommand);
  if (!quad::test::waitFor([&] { return pub.matchedReaders() > 0; }, 20s)) {
    std::cout << "no reader matched" << std::endl;
    return 1;
  }
  // Our side matched; a volatile reader drops samples from writers it has not matched yet,
  // and its side of discovery completes on its own schedule.
  std::this_thread::sleep_for(500ms);
  for (int i = 0; i < count; ++i) {
    quad::msg::VehicleCommand cmd;
    cmd.header().stamp_ns(quad::common::wallTimeNs());
    cmd.command_id(static_cast<std::uint32_t>(i + 1));
    cmd.kind(quad::msg::COMMAND_HOLD);
    cmd.altitude(1.0 + i);
    if (!pub.write(cmd)) {
      std::cout << "write failed at " << i << std::endl;
      return 1;
    }
    std::this_thread::sleep_for(1ms);
  }
  const bool acked = pub.waitForAcknowledgments(10s);
  std::cout << "sent " << count << (acked ? " acknowledged" : " NOT acknowledged") << std::endl;
  return acked ? 0 : 1;
}

int receiveCommands(Participant& p, int count, std::chrono::milliseconds timeout)
{
  quad::dds::Waker waker;
  quad::dds::Subscriber<quad::msg::VehicleCommand> sub(p, topics::kVehicleCommand, &waker);
  std::cout << "ready" << std::endl;
  const std::int64_t deadline = quad::common::steadyTimeNs() + timeout.count() * 1'000'000;
  int received = 0;
  std::uint64_t expected_seq = 1;
  while (received < count && quad::common::steadyTimeNs() < deadline) {
    waker.waitUntil(std::min(deadline, quad::common::steadyTimeNs() + 100'000'000));
    for (const auto& cmd : sub.takeAll()) {
      if (cmd.header().seq() != expected_seq) {
        std::cout << "out of order: seq " << cmd.header().seq() << ", expected " << expected_seq
                  << std::endl;
        return 1;
      }
      ++expected_seq;
      ++received;
    }
  }
  std::cout << "received " << received << " of " << count << std::endl;
  return received == count ? 0 : 1;
}

int sendState(Participant& p, const quad::dds::Topic<quad::msg::VehicleState>& topic,
              std::chrono::milliseconds duration)
{
  quad::dds::Publisher<quad::msg::VehicleState> pub(p, topic);
  const auto end = std::chrono::steady_clock::now() + duration;
  while (std::chrono::steady_clock::now() < end) {
    quad::msg::VehicleState state;
    state.header().stamp_ns(quad::common::wallTimeNs());
    state.q_WB().w(1.0);
    pub.write(state);
    std::this_thread::sleep_for(10ms);
  }
  return 0;
}

int sendHeartbeatAsState(Participant& p, std::chrono::milliseconds duration)
{
  // The wrong type on a real topic name: what a stale build of another module would do.
  const auto wrong = quad::dds::makeTopic<quad::msg::Heartbeat>(
      topics::kSimState.info.name, "heartbeat", 2.0, quad::dds::Owner::kPlant, "wrong type");
  quad::dds::Publisher<quad::msg::Heartbeat> pub(p, wrong);
  std::cout << "ready" << std::endl;
  std::this_thread::sleep_for(duration);
  return 0;
}

/// Waits for an event of `kind` on quad/sim/state and prints it.
int expectEvent(Participant& p, EventKind kind, std::chrono::milliseconds timeout)
{
  const auto found = p.events().waitFor(
      [kind](const EndpointEvent& e) { return e.kind == kind; }, timeout);
  for (const auto& e : found) {
    std::cout << "event: " << e.topic << ": " << quad::dds::toString(e.kind) << ": " << e.detail
              << std::endl;
  }
  return found.empty() ? 1 : 0;
}

int lockstepClock(Participant& p, int steps, std::chrono::milliseconds timeout,
                  std::vector<std::string> names)
{
  const auto expected = static_cast<int>(names.size());
  quad::runtime::LockstepBarrier barrier(p, std::move(names));
  quad::dds::Publisher<quad::msg::SimClock> clock(p, topics::kSimClock);
  // Participants that are up must be listening before time starts; a missing one is what
  // the barrier's timeout reports.
  quad::test::waitFor([&] { return clock.matchedReaders() >= expected; }, 5s);
  const std::int64_t start = quad::common::steadyTimeNs();
  for (int step = 1; step <= steps; ++step) {
    quad::msg::SimClock tick;
    const std::int64_t sim_ns = step * 1'000'000LL;
    tick.header().stamp_ns(sim_ns);
    tick.sim_ns(sim_ns);
    tick.step_ns(1'000'000);
    tick.lockstep(true);
    clock.write(tick);
    const auto result = barrier.waitUntilDone(sim_ns, timeout);
    if (!result.caught_up) {
      std::cout << result.message << std::endl;
      return 1;
    }
  }
  const double elapsed_s = quad::common::toSeconds(quad::common::steadyTimeNs() - start);
  std::cout << "stepped " << steps << " in " << elapsed_s * 1e3 << " ms ("
            << elapsed_s * 1e6 / steps << " us per step)" << std::endl;
  return 0;
}

int lockstepParticipant(Participant& p, const std::string& name)
{
  quad::dds::Waker waker;
  quad::dds::Subscriber<quad::msg::SimClock> clock(p, topics::kSimClock, &waker);
  quad::runtime::LockstepReporter reporter(p, name);
  std::cout << "ready" << std::endl;
  // Runs until killed by the test.
  while (true) {
    waker.waitUntil(quad::common::steadyTimeNs() + 100'000'000);
    for (const auto& tick : clock.takeAll()) {
      quad::test::waitFor([&] { return reporter.matchedBarriers() > 0; }, 5s);
      reporter.reportDone(tick.sim_ns());
    }
  }
}

}  // namespace

int main(int argc, char** argv)
{
  if (argc < 3) {
    std::cerr << "usage: dds_probe MODE ARG [ARG]\n";
    return 2;
  }
  const std::string mode = argv[1];
  const int arg = mode == "lockstep-participant" ? 0 : std::stoi(argv[2]);
  const auto ms = std::chrono::milliseconds(arg);
  try {
    Participant participant(quad::dds::optionsFromEnvironment("dds_probe_" + mode));
    if (mode == "send-commands") {
      return sendCommands(participant, arg);
    }
    if (mode == "receive-commands" && argc > 3) {
      return receiveCommands(participant, arg, std::chrono::milliseconds(std::stoi(argv[3])));
    }
    if (mode == "send-state") {
      return sendState(participant, topics::kSimState, ms);
    }
    if (mode == "receive-state-reliable") {
      auto qos = participant.readerQos(topics::kSimState.info.qos_profile);
      qos.reliability().kind = eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS;
      quad::dds::Subscriber<quad::msg::VehicleState> sub(participant, topics::kSimState, nullptr,
                                                        qos);
      std::cout << "ready" << std::endl;
      return expectEvent(participant, EventKind::kIncompatibleQos, ms);
    }
    if (mode == "send-heartbeat-as-state") {
      return sendHeartbeatAsState(participant, ms);
    }
    if (mode == "lockstep-clock" && argc > 4) {
      return lockstepClock(participant, arg, std::chrono::milliseconds(std::stoi(argv[3])),
                           std::vector<std::string>(argv + 4, argv + argc));
    }
    if (mode == "lockstep-participant") {
      return lockstepParticipant(participant, argv[2]);
    }
    if (mode == "receive-state") {
      quad::dds::Subscriber<quad::msg::VehicleState> sub(participant, topics::kSimState);
      std::cout << "ready" << std::endl;
      return expectEvent(participant, EventKind::kTypeMismatch, ms);
    }
  } catch (const std::exception& e) {
    std::cout << "dds_probe: " << e.what() << std::endl;
    return 1;
  }
  std::cerr << "dds_probe: unknown mode " << mode << "\n";
  return 2;
}
