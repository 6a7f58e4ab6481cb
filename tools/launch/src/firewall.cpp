// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/firewall.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace quad::launch {

PortRange ddsPorts(int domain)
{
  const int first = 7400 + 250 * domain;
  return {first, std::min(first + 249, 65535)};
}

FirewallRules firewallRules(const std::string& chain, PortRange ports,
                            const std::vector<int>& extra_ports, const std::vector<std::string>& admitted)
{
  using Argv = std::vector<std::string>;
  const auto iptables = [&](const Argv& args) {
    Argv argv{"iptables"};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  };
  std::string dports = fmt::format("{}:{}", ports.first, ports.last);
  for (const int p : extra_ports) {
    dports += fmt::format(",{}", p);
  }
  const Argv jump{"INPUT", "-p", "udp", "-m", "multiport", "--dports", dports, "-j", chain};
  FirewallRules r;
  r.install.push_back(iptables({"-N", chain}));
  r.install.push_back(iptables({"-A", chain, "-i", "lo", "-j", "RETURN"}));
  for (const auto& a : admitted) {
    r.install.push_back(iptables({"-A", chain, "-s", a, "-j", "RETURN"}));
  }
  r.install.push_back(iptables({"-A", chain, "-m", "comment", "--comment", "quad launch: DDS from the manifest's hosts only",
                                "-j", "DROP"}));
  Argv insert{"-I"};
  insert.insert(insert.end(), jump.begin(), jump.end());
  r.install.push_back(iptables(insert));
  Argv del{"-D"};
  del.insert(del.end(), jump.begin(), jump.end());
  r.remove.push_back(iptables(del));
  r.remove.push_back(iptables({"-F", chain}));
  r.remove.push_back(iptables({"-X", chain}));
  return r;
}

}  // namespace quad::launch
