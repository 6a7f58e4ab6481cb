// SPDX-License-Identifier: BSD-3-Clause
#include "quad/security/roles.hpp"

#include "quad/dds/topics.hpp"

namespace quad::security {

namespace {

constexpr const char* kEveryQuadTopic = "quad/*";

std::vector<std::string> ownedBy(std::initializer_list<dds::Owner> owners)
{
  std::vector<std::string> topics;
  for (const auto& t : dds::topics::kAll) {
    for (const auto o : owners) {
      if (t.owner == o) {
        topics.emplace_back(t.name);
      }
    }
  }
  return topics;
}

}  // namespace

std::vector<Role> quadRoles()
{
  using dds::Owner;
  const std::vector<std::string> all{kEveryQuadTopic};
  std::vector<Role> roles;
  for (const auto& [identity, owner] : {std::pair{"plant", Owner::kPlant}, std::pair{"estimation", Owner::kEstimation}, std::pair{"mapping", Owner::kMapping},
                                        std::pair{"planning", Owner::kPlanning}, std::pair{"control", Owner::kControl},
                                        std::pair{"display", Owner::kDisplay}}) {
    auto publish = ownedBy({owner, Owner::kEveryModule});
    publish.emplace_back(dds::topics::kFaultEvents.info.name);  // a fault layer's acknowledgements
    roles.push_back({identity, publish, all});
  }
  roles.push_back({"launch", ownedBy({Owner::kOperator, Owner::kFaultTool}), all});
  // quad bridge: what its WebSocket clients may publish (the operator's topics), and reads all.
  roles.push_back({"bridge", ownedBy({Owner::kOperator}), all});
  roles.push_back({"fault", all, all});
  roles.push_back({"replay", all, {}});
  roles.push_back({"topic_pub", all, {}});
  roles.push_back({"record", {}, all});
  roles.push_back({"topic", {}, all});
  return roles;
}

}  // namespace quad::security
