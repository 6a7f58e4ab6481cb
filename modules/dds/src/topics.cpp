// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/topics.hpp"

#include <algorithm>

namespace quad::dds {

std::string_view toString(Owner owner)
{
  switch (owner) {
    case Owner::kPlant:
      return "plant";
    case Owner::kEstimation:
      return "estimation";
    case Owner::kMapping:
      return "mapping";
    case Owner::kPlanning:
      return "planning";
    case Owner::kControl:
      return "control";
    case Owner::kDisplay:
      return "display";
    case Owner::kOperator:
      return "operator";
    case Owner::kFaultTool:
      return "fault tool";
    case Owner::kEveryModule:
      return "every module";
  }
  return "?";
}

namespace topics {

std::optional<TopicInfo> find(std::string_view name)
{
  const auto it = std::find_if(kAll.begin(), kAll.end(),
                               [name](const TopicInfo& t) { return t.name == name; });
  if (it == kAll.end()) {
    return std::nullopt;
  }
  return *it;
}

}  // namespace topics
}  // namespace quad::dds
