#include "security_command.hpp"

#include <cstdio>

#include "quad/dds/topics.hpp"

namespace quad::tools {

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

std::vector<security::Role> securityRoles()
{
  using dds::Owner;
  const std::vector<std::string> all{kEveryQuadTopic};
  std::vector<security::Role> roles;
  for (const auto& [identity, owner] : {std::pair{"plant", Owner::kPlant}, std::pair{"mapping", Owner::kMapping},
                                        std::pair{"planning", Owner::kPlanning}, std::pair{"control", Owner::kControl}}) {
    auto publish = ownedBy({owner, Owner::kEveryModule});
    publish.emplace_back(dds::topics::kFaultEvents.info.name);  // a fault layer's acknowledgements
    roles.push_back({identity, publish, all});
  }
  roles.push_back({"launch", ownedBy({Owner::kOperator, Owner::kFaultTool}), all});
  roles.push_back({"fault", all, all});
  roles.push_back({"replay", all, {}});
  roles.push_back({"topic_pub", all, {}});
  roles.push_back({"record", {}, all});
  roles.push_back({"topic", {}, all});
  return roles;
}

int securityInit(const security::InitOptions& options)
{
  const auto roles = securityRoles();
  const auto written = security::init(options, roles);
  for (const auto& f : written) {
    std::printf("%s\n", f.string().c_str());
  }
  std::printf("security: %zu identities in %s; set QUAD_SECURITY_DIR (or a manifest's security key) to it\n",
              roles.size(), options.dir.string().c_str());
  return 0;
}

}  // namespace quad::tools
