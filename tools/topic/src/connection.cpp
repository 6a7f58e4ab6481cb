// SPDX-License-Identifier: BSD-3-Clause
#include "quad/topic/connection.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <stdexcept>

#include "quad/dds/raw_type.hpp"
#include "quad/dds/topics.hpp"

namespace quad::topic {

dds::ParticipantOptions participantOptions(const std::string& name,
                                           const ConnectionOptions& connection)
{
  dds::ParticipantOptions options = dds::optionsFromEnvironment(name);
  options.observe_all = true;  // a tool looks at the whole graph
  if (connection.domain_id) {
    options.domain_id = *connection.domain_id;
  }
  if (connection.vehicle_id) {
    options.vehicle_id = *connection.vehicle_id;
  }
  return options;
}

bool selectedVehicle(const ConnectionOptions& connection, std::span<const std::uint8_t> payload)
{
  return !connection.vehicle_id || dds::payloadVehicleId(payload) == connection.vehicle_id;
}

bool matchesAnyGlob(const std::string& topic, const std::vector<std::string>& globs)
{
  return std::any_of(globs.begin(), globs.end(),
                     [&](const std::string& g) { return fnmatch(g.c_str(), topic.c_str(), 0) == 0; });
}

dds::TopicInfo requireTopic(std::string_view name)
{
  if (auto info = dds::topics::find(name)) {
    return *info;
  }
  std::string known;
  for (const auto& t : dds::topics::kAll) {
    known += "\n  " + std::string(t.name);
  }
  throw std::invalid_argument("unknown topic '" + std::string(name) +
                              "'; quad's topics are:" + known);
}

}  // namespace quad::topic
