// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The hosts of a run: this machine, Linux network namespaces that the launcher creates
/// (a bridge in this namespace, a veth link per host on a private /24, torn down at the
/// end), and machines reached over ssh. Turns a module's command into the one that runs it
/// on its host.

#include <map>
#include <string>
#include <vector>

#include "quad/launch/firewall.hpp"
#include "quad/launch/link_faults.hpp"
#include "quad/launch/manifest.hpp"

namespace quad::launch {

class HostNetwork {
public:
  /// Creates what the manifest's netns hosts need; `run_id` (the launcher's pid in hex, at
  /// most 6 digits) keeps names apart between concurrent runs and tells whose they are. Throws std::runtime_error naming the step that
  /// failed (after undoing the ones that worked), or when the subnet is already in use.
  HostNetwork(const Manifest& manifest, std::string run_id);
  ~HostNetwork();  // deletes the namespaces (and with them the veth links) and the bridge
  HostNetwork(const HostNetwork&) = delete;
  HostNetwork& operator=(const HostNetwork&) = delete;

  /// The address other hosts reach `host` at: its veth address, its ssh address, or for
  /// the local machine the bridge address (when there are namespaces) or 127.0.0.1.
  std::string address(const std::string& host) const;
  /// The addresses DDS may use on `host` (QUAD_INTERFACES): the manifest's `interfaces` for
  /// it, else its address; "" for the launcher's own (this machine's) side: a local host's,
  /// else the bridge address, or 127.0.0.1.
  std::vector<std::string> interfaces(const std::string& host) const;
  /// Installs the run's firewall (firewall.hpp) on every netns and ssh host: the domain's
  /// DDS ports, and `extra_ports`, admit only the manifest's hosts. Removed at teardown.
  /// Throws std::runtime_error naming the host and the command that failed.
  void installFirewall(int domain, const std::vector<int>& extra_ports);
  /// The namespace name of a netns host ("" for the others).
  std::string namespaceOf(const std::string& host) const;

  /// The command that runs `argv` with `env` on `host`. Local and netns hosts get `env`
  /// through the process environment; ssh hosts get it on the remote command line.
  std::vector<std::string> command(const Host& host, std::vector<std::string> argv,
                                   const std::map<std::string, std::string>& env) const;

  /// Applies a fault to a netns host's link (iptables rules on it, or the link down);
  /// throws std::runtime_error naming the host or the command that failed.
  void applyLinkFault(const LinkFault& fault) const;
  /// Undoes it; every command runs, and the first that failed is thrown.
  void healLinkFault(const LinkFault& fault) const;

private:
  void teardown() noexcept;
  LinkCommands commandsFor(const LinkFault& fault) const;

  /// The prefix that runs a command on `host` as root there (netns: ip netns exec).
  std::vector<std::string> onHost(const Host& host, std::vector<std::string> argv) const;

  const Manifest& manifest_;
  std::string run_id_;
  std::string bridge_;
  std::vector<std::vector<std::string>> firewall_removal_;  // for ssh hosts (namespaces go whole)
  std::map<std::string, std::string> namespaces_;  // host -> netns name
  std::map<std::string, std::string> links_;       // host -> its veth end in its namespace
  std::map<std::string, std::string> addresses_;
};

}  // namespace quad::launch
