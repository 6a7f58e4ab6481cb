#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "connection.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/node.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/introspection/cdr.hpp"
#include "text_format.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

namespace {
constexpr auto kReaderMatchSettle = std::chrono::milliseconds(300);
}  // namespace

nlohmann::ordered_json sampleValues(const dds::TopicInfo& info, const std::string& values)
{
  nlohmann::ordered_json value;
  try {
    value = yamlToJson(values);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("values '" + values + "': " + e.what());
  }
  if (!value.is_object()) {
    throw std::invalid_argument("values '" + values + "': expected a map of fields");
  }
  // Encoded once before any DDS work, so a typo costs nothing.
  try {
    introspection::encodeCdr(introspection::quadSchema(), info.type_name, value);
  } catch (const introspection::EncodeError& e) {
    throw std::invalid_argument(std::string(info.name) + ": " + e.what());
  }
  return value;
}

dds::RawSample encodeSample(const dds::TopicInfo& info, nlohmann::ordered_json sample, std::int64_t stamp_ns,
                            std::uint64_t seq, std::uint32_t vehicle_id, bool enforce_bounds)
{
  // The header is the publisher's to fill, as Publisher<T> does for the modules, except what
  // the values set on purpose.
  auto& header = sample["header"];
  const auto fill = [&](const char* key, auto v) {
    if (!header.contains(key)) {
      header[key] = v;
    }
  };
  fill("stamp_ns", stamp_ns);
  fill("publish_ns", common::wallTimeNs());
  fill("seq", seq);
  fill("vehicle_id", vehicle_id);
  return dds::RawSample{
      introspection::encodeCdr(introspection::quadSchema(), info.type_name, sample, {.enforce_bounds = enforce_bounds})};
}

int topicPub(const TopicPubOptions& options)
{
  const dds::TopicInfo info = requireTopic(options.topic);
  if (options.count < 1 || !(options.rate_hz > 0.0)) {
    throw std::invalid_argument("--count must be >= 1 and --rate > 0");
  }
  const nlohmann::ordered_json value = sampleValues(info, options.values);

  dds::SignalWatcher signals;
  const dds::ParticipantOptions participant_options =
      participantOptions("quad_topic_pub", options.connection);
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
    std::this_thread::sleep_for(kReaderMatchSettle);
  }

  const auto period = std::chrono::duration<double>(1.0 / options.rate_hz);
  auto next = std::chrono::steady_clock::now();
  for (int i = 1; i <= options.count && signals.received() == 0; ++i) {
    dds::RawSample raw =
        encodeSample(info, value, common::wallTimeNs(), static_cast<std::uint64_t>(i), participant_options.vehicle_id);
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
