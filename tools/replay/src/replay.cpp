// SPDX-License-Identifier: BSD-3-Clause
#include "quad/replay/replay.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <thread>

#include "quad/bag/mcap.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"

namespace quad::tools {

int replay(const ReplayOptions& options)
{
  bag::McapContents c;
  try {
    c = bag::readMcap(options.file, true);
  } catch (const bag::BagError& e) {
    std::fprintf(stderr, "replay: %s\n", e.what());
    return 1;
  }
  if (!c.complete) {
    std::fprintf(stderr, "replay: %s is incomplete (%s); replaying what it holds\n", options.file.c_str(),
                 c.problem.c_str());
  }
  runtime::SignalWatcher signals;
  dds::Participant participant(topic::participantOptions("quad_replay", options.connection));

  // The channels to publish: selected, and with a quad contract to publish them under.
  std::map<std::uint16_t, std::unique_ptr<dds::RawPublisher>> publishers;
  for (const auto& ch : c.channels) {
    if ((!options.topics.empty() && !topic::matchesAnyGlob(ch.topic, options.topics)) || topic::matchesAnyGlob(ch.topic, options.exclude)) {
      continue;
    }
    const auto contract = dds::topics::find(ch.topic);
    if (!contract) {
      std::fprintf(stderr, "replay: skipping %s: no quad topic contract names it\n", ch.topic.c_str());
      continue;
    }
    if (!options.inputs_of.empty() && dds::toString(contract->owner) == options.inputs_of) {
      continue;  // the module under test writes it: compare, do not feed
    }
    publishers[ch.id] = std::make_unique<dds::RawPublisher>(participant, *contract);
  }
  std::vector<const bag::Message*> messages;
  for (const auto& m : c.messages) {
    if (publishers.contains(m.channel_id)) {
      messages.push_back(&m);
    }
  }
  std::stable_sort(messages.begin(), messages.end(),
                   [](const bag::Message* a, const bag::Message* b) { return a->log_time < b->log_time; });
  if (messages.empty()) {
    std::fprintf(stderr, "replay: nothing to replay in %s\n", options.file.c_str());
    return 1;
  }
  const std::uint64_t t0 = messages.front()->log_time;
  const auto from = t0 + static_cast<std::uint64_t>(options.from_s * 1e9);
  const auto to = options.to_s > 0 ? t0 + static_cast<std::uint64_t>(options.to_s * 1e9) : UINT64_MAX;

  // Readers match on their own schedule: wait for each writer to have one, for a while.
  const std::int64_t deadline = common::steadyTimeNs() + common::toNanoseconds(options.wait_match_s);
  while (common::steadyTimeNs() < deadline && signals.received() == 0 &&
         std::any_of(publishers.begin(), publishers.end(), [](const auto& p) { return p.second->matchedReaders() == 0; })) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the readers' side of matching

  std::uint64_t sent = 0;
  do {
    const auto start = std::chrono::steady_clock::now();
    for (const bag::Message* m : messages) {
      if (signals.received() != 0) {
        break;
      }
      if (m->log_time < from || m->log_time > to) {
        continue;
      }
      const double offset_s = static_cast<double>(m->log_time - from) * 1e-9 / options.rate;
      std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                std::chrono::duration<double>(offset_s)));
      dds::RawSample sample{m->data};
      if (!publishers.at(m->channel_id)->write(sample)) {
        std::fprintf(stderr, "replay: a write was refused\n");
      }
      ++sent;
    }
  } while (options.loop && signals.received() == 0);
  std::fprintf(stderr, "replay: %llu messages on %zu topics\n", static_cast<unsigned long long>(sent), publishers.size());
  // Let reliable readers have the last samples before the writers go.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  return 0;
}

}  // namespace quad::tools
