// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/link_faults.hpp"

#include <fmt/format.h>

namespace quad::launch {

std::string LinkFault::describe() const
{
  switch (kind) {
    case Kind::kLoss:
      return fmt::format("loss {:g} on {}'s link", probability, host);
    case Kind::kPartition:
      return fmt::format("partition {} | {}", host, peer);
    case Kind::kDown:
      return host + "'s link down";
  }
  return "?";
}

LinkCommands linkCommands(const LinkFault& fault, const std::string& ns, const std::string& link,
                          const std::string& peer_address)
{
  using Argv = std::vector<std::string>;
  // One rule per direction; healing deletes the same rule (-D with its whole spec).
  const auto rules = [&](const Argv& match_in, const Argv& match_out) {
    LinkCommands c;
    for (const auto& [chain, dir, match] : {std::tuple{"INPUT", "-i", match_in}, std::tuple{"OUTPUT", "-o", match_out}}) {
      Argv rule{chain, dir, link};
      rule.insert(rule.end(), match.begin(), match.end());
      rule.insert(rule.end(), {"-m", "comment", "--comment", "quad fault", "-j", "DROP"});
      Argv add{"ip", "netns", "exec", ns, "iptables", "-A"};
      Argv del{"ip", "netns", "exec", ns, "iptables", "-D"};
      add.insert(add.end(), rule.begin(), rule.end());
      del.insert(del.end(), rule.begin(), rule.end());
      c.apply.push_back(add);
      c.heal.push_back(del);
    }
    return c;
  };
  switch (fault.kind) {
    case LinkFault::Kind::kLoss: {
      const Argv random{"-m", "statistic", "--mode", "random", "--probability", fmt::format("{:.6f}", fault.probability)};
      return rules(random, random);
    }
    case LinkFault::Kind::kPartition:
      return rules({"-s", peer_address}, {"-d", peer_address});
    case LinkFault::Kind::kDown:
      // Setting a link down takes its routes with it: the multicast route DDS discovery
      // needs (HostNetwork adds it) comes back with the link.
      return {{{"ip", "-n", ns, "link", "set", link, "down"}},
              {{"ip", "-n", ns, "link", "set", link, "up"},
               {"ip", "-n", ns, "route", "replace", kMulticastRoute, "dev", link}}};
  }
  return {};
}

}  // namespace quad::launch
