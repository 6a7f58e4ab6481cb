// SPDX-License-Identifier: BSD-3-Clause
#include "containers.hpp"

#include <algorithm>

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
  for (const Module* mod : members) {
    c.hosted.push_back(*mod);
    if (!mod->args.empty()) {
      problems.push_back(mod->name + " has args (" + mod->args.front() + ", ...): a hosted module takes only config and set");
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

}  // namespace quad::launch
