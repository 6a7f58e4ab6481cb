// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Host firewall rules for a run: on a host of the manifest, UDP to the DDS ports of the
/// run's domain is admitted only from the manifest's hosts (and the host itself); anyone
/// else's datagrams are dropped before any DDS participant reads them. Here only the
/// iptables commands that install and remove them; HostNetwork runs them on each host.

#include <string>
#include <vector>

namespace quad::launch {

/// The UDP ports DDS uses on `domain` with the RTPS default port mapping: 7400 + 250 × domain,
/// and the 249 after it (discovery and user traffic, multicast and every participant's
/// unicast), up to 65535.
struct PortRange {
  int first = 0;
  int last = 0;
};
PortRange ddsPorts(int domain);

struct FirewallRules {
  std::vector<std::vector<std::string>> install;
  std::vector<std::vector<std::string>> remove;  ///< undo `install`, in order
};

/// iptables commands (argv, run as root on the protected host) for a chain `chain` of the
/// run's own: UDP to `ports` (and `extra_ports`, e.g. a discovery server's) from `admitted`
/// addresses or the loopback interface goes on to the host's other rules, the rest is
/// dropped.
FirewallRules firewallRules(const std::string& chain, PortRange ports,
                            const std::vector<int>& extra_ports, const std::vector<std::string>& admitted);

}  // namespace quad::launch
