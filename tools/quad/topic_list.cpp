#include <chrono>
#include <cstdio>
#include <map>
#include <thread>

#include "quad/topic/connection.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/topics.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

namespace {

void printContracts()
{
  std::printf("%-26s %-28s %-10s %8s %11s  %-12s %s\n", "TOPIC", "TYPE", "QOS", "RATE", "STALE AFTER",
              "OWNER", "DESCRIPTION");
  for (const auto& t : dds::topics::kAll) {
    const std::string rate = t.rate_hz > 0 ? std::to_string(static_cast<int>(t.rate_hz)) + " Hz"
                                           : "event";
    const std::string stale = t.stale_after_s > 0 ? common::formatValue(t.stale_after_s) + " s" : "-";
    std::printf("%-26s %-28s %-10s %8s %11s  %-12s %s\n", std::string(t.name).c_str(),
                std::string(t.type_name).c_str(), std::string(t.qos_profile).c_str(),
                rate.c_str(), stale.c_str(), std::string(dds::toString(t.owner)).c_str(),
                std::string(t.description).c_str());
  }
}

}  // namespace

int topicList(const TopicListOptions& options)
{
  if (options.contracts) {
    printContracts();
    return 0;
  }
  dds::Participant participant(topic::participantOptions("quad_topic_list", options.connection));
  std::this_thread::sleep_for(std::chrono::duration<double>(options.wait_s));

  struct Row {
    std::string type;
    int writers = 0;
    int readers = 0;
  };
  std::map<std::string, Row> rows;
  for (const auto& e : participant.remoteEndpoints()) {
    Row& row = rows[e.topic];
    if (!row.type.empty() && row.type != e.type_name) {
      row.type += " | " + e.type_name;  // two types on one topic: show both, it is a fault
    } else {
      row.type = e.type_name;
    }
    (e.writer ? row.writers : row.readers) += 1;
  }
  if (rows.empty()) {
    std::fprintf(stderr, "no topics seen on domain %d within %.1f s\n",
                 participant.options().domain_id, options.wait_s);
    return 0;
  }
  std::printf("%-26s %-28s %7s %7s  %s\n", "TOPIC", "TYPE", "WRITERS", "READERS", "CONTRACT");
  for (const auto& [name, row] : rows) {
    const auto contract = dds::topics::find(name);
    std::string note = "not declared by quad";
    if (contract) {
      note = contract->type_name == row.type ? std::string(dds::toString(contract->owner))
                                             : "TYPE DIFFERS: expected " +
                                                   std::string(contract->type_name);
    }
    std::printf("%-26s %-28s %7d %7d  %s\n", name.c_str(), row.type.c_str(), row.writers,
                row.readers, note.c_str());
  }
  return 0;
}

}  // namespace quad::tools
