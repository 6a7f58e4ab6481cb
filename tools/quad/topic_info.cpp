#include <chrono>
#include <cstdio>
#include <thread>

#include "quad/topic/connection.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/topics.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

int topicInfo(const TopicInfoOptions& options)
{
  const dds::TopicInfo info = topic::requireTopic(options.topic);
  std::printf("topic:       %s\n", std::string(info.name).c_str());
  std::printf("type:        %s (idl/%s)\n", std::string(info.type_name).c_str(), std::string(info.idl_file).c_str());
  std::printf("qos:         %s (configs/dds/quad_qos.xml)\n", std::string(info.qos_profile).c_str());
  std::printf("rate:        %s\n", info.rate_hz > 0 ? (std::to_string(static_cast<int>(info.rate_hz)) + " Hz").c_str() : "event");
  std::printf("stale after: %s\n",
              info.stale_after_s > 0 ? (common::formatValue(info.stale_after_s) + " s without a sample (sim time)").c_str()
                                     : "not judged");
  std::printf("written by:  %s\n", std::string(dds::toString(info.owner)).c_str());
  std::printf("what:        %s\n", std::string(info.description).c_str());

  dds::Participant participant(topic::participantOptions("quad_topic_info", options.connection));
  std::this_thread::sleep_for(std::chrono::duration<double>(options.wait_s));
  int writers = 0;
  int readers = 0;
  for (const bool writer : {true, false}) {
    std::printf("%s:\n", writer ? "writers" : "readers");
    for (const auto& e : participant.remoteEndpoints()) {
      if (e.writer != writer || e.topic != info.name) {
        continue;
      }
      (writer ? writers : readers) += 1;
      std::printf("  %-20s on %-28s %s, %s%s\n", e.participant.empty() ? "?" : e.participant.c_str(),
                  e.host.empty() ? "?" : e.host.c_str(), e.reliable ? "reliable" : "best effort",
                  e.transient_local ? "transient local" : "volatile",
                  e.type_name == info.type_name ? "" : (", TYPE " + e.type_name + " DIFFERS").c_str());
    }
  }
  std::printf("%d writers, %d readers seen on domain %d within %.1f s\n", writers, readers,
              participant.options().domain_id, options.wait_s);
  return 0;
}

}  // namespace quad::tools
