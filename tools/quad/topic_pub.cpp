// SPDX-License-Identifier: BSD-3-Clause
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"
#include "quad/topic/samples.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

int topicPub(const TopicPubOptions& options)
{
  const dds::TopicInfo info = topic::requireTopic(options.topic);
  if (options.count < 1 || !(options.rate_hz > 0.0)) {
    throw std::invalid_argument("--count must be >= 1 and --rate > 0");
  }
  const nlohmann::ordered_json value = topic::sampleValues(info, options.values);

  runtime::SignalWatcher signals;
  const dds::ParticipantOptions participant_options =
      topic::participantOptions("quad_topic_pub", options.connection);
  dds::Participant participant(participant_options);
  dds::RawPublisher publisher(participant, info);

  const std::int64_t match_deadline =
      common::steadyTimeNs() + common::toNanoseconds(options.wait_match_s);
  while (publisher.matchedReaders() == 0 && common::steadyTimeNs() < match_deadline &&
         signals.received() == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (publisher.matchedReaders() == 0) {
    std::fprintf(stderr, "quad topic pub: no reader of %s within %.1f s; publishing anyway\n",
                 options.topic.c_str(), options.wait_match_s);
  } else {
    // A volatile reader drops samples from a writer it has not matched yet, and the readers'
    // side of discovery completes on its own schedule: give it a moment.
    std::this_thread::sleep_for(dds::kReaderMatchSettle);
  }

  const auto period = std::chrono::duration<double>(1.0 / options.rate_hz);
  auto next = std::chrono::steady_clock::now();
  for (int i = 1; i <= options.count && signals.received() == 0; ++i) {
    dds::RawSample raw =
        topic::encodeSample(info, value, common::wallTimeNs(), static_cast<std::uint64_t>(i), participant_options.vehicle_id);
    if (!publisher.write(raw)) {
      std::fprintf(stderr, "quad topic pub: %s: write %d refused\n", options.topic.c_str(), i);
      return 1;
    }
    std::printf("published %s #%d\n", options.topic.c_str(), i);
    std::fflush(stdout);
    if (i < options.count) {
      next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
      std::this_thread::sleep_until(next);
    }
  }
  if (publisher.matchedReaders() > 0 && !publisher.waitForAcknowledgments(std::chrono::seconds(5))) {
    std::fprintf(stderr, "quad topic pub: %s: not every reader acknowledged within 5 s\n",
                 options.topic.c_str());
    return 1;
  }
  return 0;
}

}  // namespace quad::tools
