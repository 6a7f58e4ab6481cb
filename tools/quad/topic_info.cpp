// SPDX-License-Identifier: BSD-3-Clause
#include <chrono>
#include <cstdio>
#include <thread>

#include <nlohmann/json.hpp>

#include "quad/topic/connection.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/topics.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

int topicInfo(const TopicInfoOptions& options)
{
  const dds::TopicInfo info = topic::requireTopic(options.topic);
  dds::Participant participant(topic::participantOptions("quad_topic_info", options.connection));
  if (!options.json) {
    std::printf("topic:       %s\n", std::string(info.name).c_str());
    std::printf("type:        %s (idl/%s)\n", std::string(info.type_name).c_str(), std::string(info.idl_file).c_str());
    std::printf("qos:         %s (configs/dds/quad_qos.xml)\n", std::string(info.qos_profile).c_str());
    std::printf("rate:        %s\n", info.rate_hz > 0 ? (std::to_string(static_cast<int>(info.rate_hz)) + " Hz").c_str() : "event");
    std::printf("stale after: %s\n",
                info.stale_after_s > 0 ? (common::formatValue(info.stale_after_s) + " s without a sample (sim time)").c_str()
                                       : "not judged");
    std::printf("written by:  %s\n", std::string(dds::toString(info.owner)).c_str());
    std::printf("what:        %s\n", std::string(info.description).c_str());
    std::fflush(stdout);
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(options.wait_s));
  nlohmann::ordered_json seen{{"writers", nlohmann::ordered_json::array()}, {"readers", nlohmann::ordered_json::array()}};
  for (const bool writer : {true, false}) {
    if (!options.json) {
      std::printf("%s:\n", writer ? "writers" : "readers");
    }
    for (const auto& e : participant.remoteEndpoints()) {
      if (e.writer != writer || e.topic != info.name) {
        continue;
      }
      seen[writer ? "writers" : "readers"].push_back({{"participant", e.participant},
                                                     {"host", e.host},
                                                     {"reliable", e.reliable},
                                                     {"transient_local", e.transient_local},
                                                     {"type", e.type_name}});
      if (!options.json) {
        std::printf("  %-20s on %-28s %s, %s%s\n", e.participant.empty() ? "?" : e.participant.c_str(),
                    e.host.empty() ? "?" : e.host.c_str(), e.reliable ? "reliable" : "best effort",
                    e.transient_local ? "transient local" : "volatile",
                    e.type_name == info.type_name ? "" : (", TYPE " + e.type_name + " DIFFERS").c_str());
      }
    }
  }
  const int domain = participant.options().domain_id;
  if (options.json) {
    nlohmann::ordered_json j{
        {"topic", info.name},
        {"type", info.type_name},
        {"idl", info.idl_file},
        {"qos", info.qos_profile},
        {"rate_hz", info.rate_hz > 0 ? nlohmann::ordered_json(info.rate_hz) : nlohmann::ordered_json(nullptr)},
        {"stale_after_s", info.stale_after_s > 0 ? nlohmann::ordered_json(info.stale_after_s) : nlohmann::ordered_json(nullptr)},
        {"owner", dds::toString(info.owner)},
        {"description", info.description},
        {"domain", domain},
        {"wait_s", options.wait_s}};
    j["writers"] = seen["writers"];
    j["readers"] = seen["readers"];
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("%zu writers, %zu readers seen on domain %d within %.1f s\n", seen["writers"].size(), seen["readers"].size(),
              domain, options.wait_s);
  return 0;
}

}  // namespace quad::tools
