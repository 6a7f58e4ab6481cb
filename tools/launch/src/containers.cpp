// SPDX-License-Identifier: BSD-3-Clause
#include "containers.hpp"

#include <algorithm>

#include "quad/common/identity.hpp"

namespace quad::launch {

Module composeContainer(const ContainerSpec& spec, const std::vector<const Module*>& members,
                        const std::filesystem::path& program, const ProgramLookup& lookup,
                        std::vector<std::string>& problems)
{
  Module c;
  c.name = spec.name;
  c.kind = kContainerKind;
  c.program = program;
  c.host = members.front()->host;
  c.ready_timeout_s = 0.0;
  c.vehicle = members.front()->vehicle;  // a fleet's container holds one vehicle's modules
  for (const Module* mod : members) {
    c.hosted.push_back(*mod);
    if (!mod->args.empty()) {
      problems.push_back(mod->name + " has args (" + mod->args.front() + ", ...): a hosted module takes only config and set");
    }
    if (mod->vehicle != c.vehicle) {
      problems.push_back(mod->name + " and " + members.front()->name +
                         " serve two vehicles: a container's process has one vehicle id");
    }
    if (mod->host != c.host) {
      problems.push_back(mod->name + " runs on " + mod->host + " and " + members.front()->name + " on " + c.host +
                         ": a container's modules share one host");
    }
    for (const auto& [k, v] : mod->environment) {
      const auto [it, fresh] = c.environment.emplace(k, v);
      if (!fresh && it->second != v) {
        problems.push_back(mod->name + " sets " + k + "=" + v + " and another of its modules " + k + "=" + it->second +
                           ": one process has one environment");
      }
    }
    for (const auto& topic : mod->needs) {
      const auto owner = lookup.topic_owner ? lookup.topic_owner(topic) : std::nullopt;
      const bool own = owner && std::any_of(members.begin(), members.end(), [&](const Module* m) { return m->kind == *owner; });
      if (!own && std::find(c.needs.begin(), c.needs.end(), topic) == c.needs.end()) {
        c.needs.push_back(topic);
      }
    }
    c.ready_timeout_s = std::max(c.ready_timeout_s, mod->ready_timeout_s);
    c.respawn = std::max(c.respawn, mod->respawn);
    c.backoff_s = std::max(c.backoff_s, mod->backoff_s);
    c.ends_run = c.ends_run || mod->ends_run;
  }
  return c;
}

void checkContainerIdentity(const Module& container, const std::filesystem::path& security_dir,
                            std::vector<std::string>& problems)
{
  std::vector<std::string> kinds;
  std::string listed;
  for (const Module& hosted : container.hosted) {
    kinds.push_back(hosted.kind);
    listed += (listed.empty() ? "" : ",") + hosted.kind;
  }
  const auto files = common::securityFiles(security_dir, common::securityIdentity(common::containerName(kinds)));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(files.certificate, ec)) {
    problems.push_back("no " + files.certificate.filename().string() + " in " + security_dir.string() +
                       ": a container has one identity; make it with quad security init " + security_dir.string() +
                       " --container " + listed);
  }
}

}  // namespace quad::launch
