// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "quad/common/time.hpp"
#include "quad/dds/raw_type.hpp"
#include "quad/dds/waker.hpp"
#include "quad/runtime/node.hpp"
#include "quad/topic/connection.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

int topicHz(const TopicHzOptions& options)
{
  const dds::TopicInfo info = topic::requireTopic(options.topic);
  runtime::SignalWatcher signals;
  dds::Participant participant(topic::participantOptions("quad_topic_hz", options.connection));
  dds::Waker waker;
  dds::RawSubscriber subscriber(participant, info, &waker);
  const std::string expected = info.rate_hz > 0 ? std::to_string(static_cast<int>(info.rate_hz)) + " Hz" : "event";
  const nlohmann::ordered_json contract_hz = info.rate_hz > 0 ? nlohmann::ordered_json(info.rate_hz) : nullptr;

  const std::int64_t start = common::steadyTimeNs();
  const std::int64_t window = common::toNanoseconds(options.window_s);
  std::int64_t window_end = start + window;
  std::int64_t last = 0;
  std::uint64_t count = 0, total = 0;
  double min_dt = std::numeric_limits<double>::infinity(), max_dt = 0.0;
  while (signals.received() == 0) {
    const std::int64_t now = common::steadyTimeNs();
    if (options.duration_s > 0 && now - start >= common::toNanoseconds(options.duration_s)) {
      break;
    }
    dds::RawSample sample;
    while (subscriber.take(sample)) {
      if (!topic::selectedVehicle(options.connection, sample.payload)) {
        continue;
      }
      const std::int64_t t = common::steadyTimeNs();
      if (last != 0) {
        const double dt = common::toSeconds(t - last);
        min_dt = std::min(min_dt, dt);
        max_dt = std::max(max_dt, dt);
      }
      last = t;
      ++count;
      ++total;
    }
    if (now >= window_end) {
      const double rate = static_cast<double>(count) / options.window_s;
      if (options.json) {
        const auto interval = [&](double dt) { return count > 1 ? nlohmann::ordered_json(dt * 1e3) : nullptr; };
        std::printf("%s\n", nlohmann::ordered_json{{"kind", "window"},
                                                   {"topic", info.name},
                                                   {"window_s", options.window_s},
                                                   {"samples", count},
                                                   {"rate_hz", rate},
                                                   {"contract_hz", contract_hz},
                                                   {"min_interval_ms", interval(min_dt)},
                                                   {"max_interval_ms", interval(max_dt)}}
                                 .dump()
                                 .c_str());
      } else {
        std::printf("%s: %.1f Hz (contract: %s)", std::string(info.name).c_str(), rate, expected.c_str());
        if (count > 1) {
          std::printf(", intervals %.2f to %.2f ms", min_dt * 1e3, max_dt * 1e3);
        }
        std::printf("\n");
      }
      std::fflush(stdout);
      count = 0;
      min_dt = std::numeric_limits<double>::infinity();
      max_dt = 0.0;
      window_end += window;
    }
    waker.waitUntil(window_end);
  }
  const double seconds = common::toSeconds(common::steadyTimeNs() - start);
  if (options.json) {
    std::printf("%s\n", nlohmann::ordered_json{{"kind", "total"},
                                               {"topic", info.name},
                                               {"seconds", seconds},
                                               {"samples", total},
                                               {"rate_hz", static_cast<double>(total) / seconds},
                                               {"contract_hz", contract_hz}}
                             .dump()
                             .c_str());
    return 0;
  }
  std::printf("%s: %llu samples in %.1f s, %.1f Hz on average (contract: %s)\n", std::string(info.name).c_str(),
              static_cast<unsigned long long>(total), seconds, static_cast<double>(total) / seconds, expected.c_str());
  return 0;
}

}  // namespace quad::tools
