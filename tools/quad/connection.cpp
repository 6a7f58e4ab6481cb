#include "connection.hpp"

#include <stdexcept>

#include "quad/dds/topics.hpp"

namespace quad::tools {

dds::ParticipantOptions participantOptions(const std::string& name,
                                           const ConnectionOptions& connection)
{
  dds::ParticipantOptions options = dds::optionsFromEnvironment(name);
  options.observe_all = true;  // a tool looks at the whole graph
  if (connection.domain_id) {
    options.domain_id = *connection.domain_id;
  }
  return options;
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

}  // namespace quad::tools
