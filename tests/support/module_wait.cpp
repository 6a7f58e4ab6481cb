// SPDX-License-Identifier: BSD-3-Clause
#include "module_wait.hpp"

#include <algorithm>
#include <functional>

#include "quad/dds/participant.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "wait.hpp"

namespace quad::test {

namespace {

/// Waits for a heartbeat of `module` that `holds`. Each try joins the domain with a new
/// participant for at most 5 s: should one participant's discovery stall (seen once under a
/// parallel test load: a plant running for 10 s and never discovered), the next starts afresh.
bool waitForHeartbeat(int domain, const std::string& module, const std::function<bool(const msg::Heartbeat&)>& holds,
                      std::chrono::milliseconds timeout)
{
  const auto end = std::chrono::steady_clock::now() + timeout;
  do {
    dds::ParticipantOptions options;
    options.name = "quad_test_wait";
    options.domain_id = domain;
    options.transport = dds::Transport::kUdp;
    dds::Participant participant(options);
    dds::Subscriber<msg::Heartbeat> heartbeats(participant, dds::topics::kHeartbeat);
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
    const bool seen = waitFor(
        [&] {
          for (const auto& hb : heartbeats.takeAll()) {
            if (hb.module_name().to_string() == module && holds(hb)) {
              return true;
            }
          }
          return false;
        },
        std::min(left, std::chrono::milliseconds(5000)));
    if (seen) {
      return true;
    }
  } while (std::chrono::steady_clock::now() < end);
  return false;
}

}  // namespace

bool waitForRunningModule(int domain, const std::string& module, std::chrono::milliseconds timeout)
{
  return waitForHeartbeat(
      domain, module, [](const msg::Heartbeat& hb) { return hb.state() == msg::MODULE_RUNNING; }, timeout);
}

bool waitForModuleErrors(int domain, const std::string& module, std::uint64_t errors, std::chrono::milliseconds timeout)
{
  return waitForHeartbeat(
      domain, module, [errors](const msg::Heartbeat& hb) { return hb.errors() >= errors; }, timeout);
}

bool waitForReader(int domain, const std::string& topic, std::chrono::milliseconds timeout)
{
  dds::ParticipantOptions options;
  options.name = "quad_test_wait";
  options.domain_id = domain;
  options.transport = dds::Transport::kUdp;
  const dds::Participant participant(options);
  return waitFor(
      [&] {
        const auto seen = participant.remoteEndpoints();
        return std::any_of(seen.begin(), seen.end(),
                           [&](const dds::RemoteEndpoint& e) { return !e.writer && e.topic == topic; });
      },
      timeout);
}

}  // namespace quad::test
