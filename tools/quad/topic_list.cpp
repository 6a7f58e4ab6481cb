// SPDX-License-Identifier: BSD-3-Clause
#include <chrono>
#include <cstdio>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "quad/topic/connection.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/topics.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

namespace {

void printContracts(bool json)
{
  nlohmann::ordered_json contracts = nlohmann::ordered_json::array();
  if (!json) {
    std::printf("%-26s %-28s %-10s %8s %11s  %-12s %s\n", "TOPIC", "TYPE", "QOS", "RATE", "STALE AFTER", "OWNER",
                "DESCRIPTION");
  }
  for (const auto& t : dds::topics::kAll) {
    if (json) {
      contracts.push_back({{"topic", t.name},
                           {"type", t.type_name},
                           {"qos", t.qos_profile},
                           {"rate_hz", t.rate_hz > 0 ? nlohmann::ordered_json(t.rate_hz) : nlohmann::ordered_json(nullptr)},
                           {"stale_after_s", t.stale_after_s > 0 ? nlohmann::ordered_json(t.stale_after_s)
                                                                 : nlohmann::ordered_json(nullptr)},
                           {"owner", dds::toString(t.owner)},
                           {"description", t.description}});
      continue;
    }
    const std::string rate = t.rate_hz > 0 ? std::to_string(static_cast<int>(t.rate_hz)) + " Hz" : "event";
    const std::string stale = t.stale_after_s > 0 ? common::formatValue(t.stale_after_s) + " s" : "-";
    std::printf("%-26s %-28s %-10s %8s %11s  %-12s %s\n", std::string(t.name).c_str(), std::string(t.type_name).c_str(),
                std::string(t.qos_profile).c_str(), rate.c_str(), stale.c_str(),
                std::string(dds::toString(t.owner)).c_str(), std::string(t.description).c_str());
  }
  if (json) {
    std::printf("%s\n", nlohmann::ordered_json{{"contracts", contracts}}.dump(2).c_str());
  }
}

}  // namespace

int topicList(const TopicListOptions& options)
{
  if (options.contracts) {
    printContracts(options.json);
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
  const int domain = participant.options().domain_id;
  if (options.json) {
    nlohmann::ordered_json topics = nlohmann::ordered_json::array();
    for (const auto& [name, row] : rows) {
      const auto contract = dds::topics::find(name);
      topics.push_back({{"topic", name},
                        {"type", row.type},
                        {"writers", row.writers},
                        {"readers", row.readers},
                        {"declared", contract.has_value()},
                        {"owner", contract ? nlohmann::ordered_json(dds::toString(contract->owner)) : nullptr},
                        {"type_matches", contract && contract->type_name == row.type}});
    }
    std::printf("%s\n",
                nlohmann::ordered_json{{"domain", domain}, {"wait_s", options.wait_s}, {"topics", topics}}.dump(2).c_str());
    return 0;
  }
  if (rows.empty()) {
    std::fprintf(stderr, "no topics seen on domain %d within %.1f s\n", domain, options.wait_s);
    return 0;
  }
  std::printf("%-26s %-28s %7s %7s  %s\n", "TOPIC", "TYPE", "WRITERS", "READERS", "CONTRACT");
  for (const auto& [name, row] : rows) {
    const auto contract = dds::topics::find(name);
    std::string note = "not declared by quad";
    if (contract) {
      note = contract->type_name == row.type ? std::string(dds::toString(contract->owner))
                                             : "TYPE DIFFERS: expected " + std::string(contract->type_name);
    }
    std::printf("%-26s %-28s %7d %7d  %s\n", name.c_str(), row.type.c_str(), row.writers, row.readers, note.c_str());
  }
  return 0;
}

}  // namespace quad::tools
