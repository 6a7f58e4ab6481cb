// SPDX-License-Identifier: BSD-3-Clause
#include <cstdio>
#include <iostream>

#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/introspection/cdr.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"
#include "quad/topic/text_format.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

int topicEcho(const TopicEchoOptions& options)
{
  const dds::TopicInfo info = topic::requireTopic(options.topic);
  runtime::SignalWatcher signals;
  dds::Participant participant(topic::participantOptions("quad_topic_echo", options.connection));
  dds::Waker waker;
  signals.onSignal([&waker](int) { waker.notify(); });
  participant.events().setNotifier([&waker] { waker.notify(); });
  // Every sample that arrives is printed: a deep history keeps the ones that come while the
  // last were being printed (a "newest only" topic's own history keeps one).
  dds::RawSubscriber subscriber(participant, info, &waker, dds::withDepth(participant.readerQos(info), 1024));

  const auto& schema = introspection::quadSchema();
  const introspection::DecodeOptions decode{.max_elements = options.max_elements};
  const std::int64_t start = common::steadyTimeNs();
  const std::int64_t deadline =
      options.timeout_s > 0 ? start + common::toNanoseconds(options.timeout_s) : INT64_MAX;
  int printed = 0;
  int malformed = 0;
  while (signals.received() == 0 && (options.count == 0 || printed < options.count)) {
    if (common::steadyTimeNs() >= deadline) {
      std::fprintf(stderr,
                   "quad topic echo: %s: %d of %d sample(s) within %.1f s (%d writer(s) matched)\n",
                   options.topic.c_str(), printed, options.count, options.timeout_s,
                   subscriber.matchedWriters());
      return 1;
    }
    waker.waitUntil(std::min(deadline, common::steadyTimeNs() + 100'000'000));
    for (const auto& event : participant.events().drain()) {
      if (event.kind == dds::EventKind::kIncompatibleQos ||
          event.kind == dds::EventKind::kTypeMismatch) {
        std::fprintf(stderr, "quad topic echo: %s: %s: %s\n", event.topic.c_str(),
                     std::string(dds::toString(event.kind)).c_str(), event.detail.c_str());
      }
    }
    dds::RawSample sample;
    while ((options.count == 0 || printed < options.count) && subscriber.take(sample)) {
      if (!topic::selectedVehicle(options.connection, sample.payload)) {
        continue;
      }
      try {
        const auto value = introspection::decodeCdr(schema, info.type_name, sample.payload, decode);
        if (options.json) {
          std::cout << value.dump() << "\n";
        } else {
          std::cout << topic::toYaml(value) << "---\n";
        }
        std::cout.flush();
        ++printed;
      } catch (const introspection::DecodeError& e) {
        ++malformed;
        std::fprintf(stderr, "quad topic echo: %s: malformed sample (%zu bytes): %s\n",
                     options.topic.c_str(), sample.payload.size(), e.what());
      }
    }
  }
  return malformed > 0 && printed == 0 ? 1 : 0;
}

}  // namespace quad::tools
