// SPDX-License-Identifier: BSD-3-Clause
// How quad compares two runs' recordings: the topics paced by sim time, without the members
// that hold wall-clock or compute times (the topic contracts' lists).
#include <cstdio>

#include <nlohmann/json.hpp>

#include "quad/dds/topics.hpp"
#include "quad/replay/replay.hpp"

namespace quad::tools {

bag::CompareOptions simPacedComparison(std::function<bool(const std::string& topic)> selected)
{
  bag::CompareOptions compare;
  compare.selected = std::move(selected);
  compare.clock_topic = dds::topics::kSimClock.info.name;
  compare.ignored_fields.assign(dds::topics::kWallClockFields.begin(), dds::topics::kWallClockFields.end());
  return compare;
}

void printComparison(const bag::Comparison& c, bool json)
{
  if (json) {
    nlohmann::ordered_json j;
    j["identical"] = c.differences.empty();
    j["topics"] = c.topics;
    j["equal_messages"] = c.messages;
    j["differences"] = nlohmann::ordered_json::array();
    for (const auto& d : c.differences) {
      j["differences"].push_back({{"topic", d.topic}, {"index", d.index}, {"stamp_ns", d.stamp_ns}, {"field", d.field},
                                  {"first", d.first}, {"second", d.second}});
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else if (c.differences.empty()) {
    std::printf("identical: %zu topics, %llu messages each\n", c.topics, static_cast<unsigned long long>(c.messages));
  } else {
    std::printf("differ: %zu of %zu topics (%llu messages agree before the first difference of each)\n",
                c.differences.size(), c.topics, static_cast<unsigned long long>(c.messages));
    for (const auto& d : c.differences) {
      std::printf("  %s #%llu (t = %.3f s): %s: %s / %s\n", d.topic.c_str(), static_cast<unsigned long long>(d.index),
                  static_cast<double>(d.stamp_ns) * 1e-9, d.field.c_str(), d.first.c_str(), d.second.c_str());
    }
  }
}

}  // namespace quad::tools
