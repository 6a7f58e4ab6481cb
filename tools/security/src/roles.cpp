// SPDX-License-Identifier: BSD-3-Clause
#include "quad/security/roles.hpp"

#include <algorithm>
#include <stdexcept>

#include "quad/common/identity.hpp"
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

constexpr std::pair<const char*, dds::Owner> kModules[] = {
    {"plant", dds::Owner::kPlant},       {"estimation", dds::Owner::kEstimation}, {"mapping", dds::Owner::kMapping},
    {"planning", dds::Owner::kPlanning}, {"control", dds::Owner::kControl},       {"display", dds::Owner::kDisplay}};

Role moduleRole(const char* identity, dds::Owner owner)
{
  auto publish = ownedBy({owner, dds::Owner::kEveryModule});
  publish.emplace_back(dds::topics::kFaultEvents.info.name);  // a fault layer's acknowledgements
  return {identity, publish, {kEveryQuadTopic}};
}

}  // namespace

std::vector<Role> quadRoles()
{
  using dds::Owner;
  const std::vector<std::string> all{kEveryQuadTopic};
  std::vector<Role> roles;
  for (const auto& [identity, owner] : kModules) {
    roles.push_back(moduleRole(identity, owner));
  }
  // The launcher's observer and the recorder hold a lockstep run's first step until they
  // have matched what they score and record: they report on the lockstep topic.
  const std::string lockstep(dds::topics::kLockstep.info.name);
  auto launch = ownedBy({Owner::kOperator, Owner::kFaultTool});
  launch.push_back(lockstep);
  roles.push_back({"launch", launch, all});
  // quad bridge: what its WebSocket clients may publish (the operator's topics), and reads all.
  roles.push_back({"bridge", ownedBy({Owner::kOperator}), all});
  roles.push_back({"fault", all, all});
  roles.push_back({"replay", all, {}});
  roles.push_back({"topic_pub", all, {}});
  roles.push_back({"record", {lockstep}, all});
  roles.push_back({"topic", {}, all});
  return roles;
}

Role containerRole(const std::vector<std::string>& modules)
{
  if (modules.empty()) {
    throw std::invalid_argument("a container hosts at least one module");
  }
  Role role{common::containerName(modules), {}, {kEveryQuadTopic}};
  for (auto name = modules.begin(); name != modules.end(); ++name) {
    const auto* entry =
        std::find_if(std::begin(kModules), std::end(kModules), [&](const auto& m) { return *name == m.first; });
    if (entry == std::end(kModules)) {
      std::string known;
      for (const auto& m : kModules) {
        known += (known.empty() ? "" : ", ") + std::string(m.first);
      }
      throw std::invalid_argument("no module '" + *name + "' (modules: " + known + ")");
    }
    if (std::find(modules.begin(), name, *name) != name) {
      throw std::invalid_argument("module '" + *name + "' named twice: a container hosts a module once");
    }
    for (auto& topic : moduleRole(entry->first, entry->second).publish) {
      if (std::find(role.publish.begin(), role.publish.end(), topic) == role.publish.end()) {
        role.publish.push_back(std::move(topic));
      }
    }
  }
  return role;
}

}  // namespace quad::security
