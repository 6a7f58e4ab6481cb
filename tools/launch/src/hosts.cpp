// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/hosts.hpp"

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "quad/process/run.hpp"
#include "quad/process/shell_quote.hpp"

namespace quad::launch {

namespace {

/// Deletes the namespaces, bridges and links of launchers that no longer run (killed with
/// SIGKILL, so their teardown never ran).
void removeAbandonedNetworks()
{
  // Names carry the launcher's pid in hex: quad-<pid>-<host>, qb<pid>, qv<pid>x<n>a.
  const auto alive = [](const std::string& hex) {
    try {
      const auto pid = static_cast<pid_t>(std::stol(hex, nullptr, 16));
      return ::kill(pid, 0) == 0 || errno != ESRCH;
    } catch (const std::exception&) {
      return true;  // not ours to judge
    }
  };
  std::istringstream namespaces(process::run({"ip", "netns", "list"}).output);
  for (std::string line; std::getline(namespaces, line);) {
    const std::string name = line.substr(0, line.find(' '));
    const auto dash = name.find('-', 5);
    if (name.starts_with("quad-") && dash != std::string::npos && !alive(name.substr(5, dash - 5))) {
      process::run({"ip", "netns", "delete", name});
    }
  }
  std::istringstream links(process::run({"ip", "-o", "link", "show"}).output);
  for (std::string line; std::getline(links, line);) {
    // "12: qb1b25: <...>" or "13: qv1b25x0a@if12: <...>"
    const auto colon = line.find(": ");
    if (colon == std::string::npos) {
      continue;
    }
    std::string name = line.substr(colon + 2);
    name = name.substr(0, std::min(name.find(':'), name.find('@')));
    if ((name.starts_with("qb") && !alive(name.substr(2))) ||
        (name.starts_with("qv") && name.find('x') != std::string::npos && !alive(name.substr(2, name.find('x') - 2)))) {
      process::run({"ip", "link", "delete", name});
    }
  }
}

}  // namespace

HostNetwork::HostNetwork(const Manifest& manifest, std::string run_id) : manifest_(manifest), run_id_(run_id)
{
  int next = 2;
  for (const auto& h : manifest.hosts) {
    if (h.kind == HostKind::kSsh) {
      const auto at = h.address.find('@');
      addresses_[h.name] = at == std::string::npos ? h.address : h.address.substr(at + 1);
    } else if (h.kind == HostKind::kNetns) {
      addresses_[h.name] = manifest.subnet + "." + std::to_string(next++);
    }
  }
  const bool namespaces = manifest.usesNamespaces();
  for (const auto& h : manifest.hosts) {
    if (h.kind == HostKind::kLocal) {
      addresses_[h.name] = namespaces ? manifest.subnet + ".1" : "127.0.0.1";
    }
  }
  if (!namespaces) {
    return;
  }
  // What a launcher killed with SIGKILL left behind would hold our subnet.
  removeAbandonedNetworks();
  // A subnet some interface already has would route our traffic elsewhere, or collide
  // with a concurrent run: refuse it.
  const std::string prefix = " " + manifest.subnet + ".";
  const std::string in_use = process::run({"ip", "-o", "-4", "addr", "show"}).output;
  if (in_use.find("inet" + prefix) != std::string::npos) {
    throw std::runtime_error(manifest.file.string() + ":subnet: " + manifest.subnet +
                             ": already used by an interface of this machine (another run?); pick another");
  }
  try {
    bridge_ = "qb" + run_id;
    process::runChecked({"ip", "link", "add", bridge_, "type", "bridge"});
    process::runChecked({"ip", "addr", "add", manifest.subnet + ".1/24", "dev", bridge_});
    process::runChecked({"ip", "link", "set", bridge_, "up"});
    int index = 0;
    for (const auto& h : manifest.hosts) {
      if (h.kind != HostKind::kNetns) {
        continue;
      }
      const std::string ns = "quad-" + run_id + "-" + h.name;
      const std::string outside = "qv" + run_id + "x" + std::to_string(index) + "a";
      const std::string inside = "qv" + run_id + "x" + std::to_string(index) + "b";
      ++index;
      process::runChecked({"ip", "netns", "add", ns});
      namespaces_[h.name] = ns;
      process::runChecked({"ip", "link", "add", outside, "type", "veth", "peer", "name", inside});
      process::runChecked({"ip", "link", "set", inside, "netns", ns});
      process::runChecked({"ip", "link", "set", outside, "master", bridge_, "up"});
      process::runChecked({"ip", "-n", ns, "addr", "add", addresses_[h.name] + "/24", "dev", inside});
      process::runChecked({"ip", "-n", ns, "link", "set", inside, "up"});
      process::runChecked({"ip", "-n", ns, "link", "set", "lo", "up"});
      // Without a route to them, multicast datagrams (DDS discovery) cannot be sent.
      process::runChecked({"ip", "-n", ns, "route", "add", kMulticastRoute, "dev", inside});
      links_[h.name] = inside;
    }
  } catch (...) {
    teardown();
    throw;
  }
}

HostNetwork::~HostNetwork() { teardown(); }

void HostNetwork::teardown() noexcept
{
  for (const auto& argv : firewall_removal_) {
    try {
      process::runChecked(argv);
    } catch (const std::exception&) {
    }
  }
  firewall_removal_.clear();
  for (const auto& [host, ns] : namespaces_) {
    try {
      process::runChecked({"ip", "netns", "delete", ns});  // takes its veth end, and so the pair, with it
    } catch (const std::exception&) {
    }
  }
  namespaces_.clear();
  if (!bridge_.empty()) {
    try {
      process::runChecked({"ip", "link", "delete", bridge_});
    } catch (const std::exception&) {
    }
    bridge_.clear();
  }
}

std::string HostNetwork::address(const std::string& host) const
{
  const auto it = addresses_.find(host);
  return it == addresses_.end() ? "127.0.0.1" : it->second;
}

LinkCommands HostNetwork::commandsFor(const LinkFault& fault) const
{
  const auto link = links_.find(fault.host);
  if (link == links_.end()) {
    throw std::runtime_error("host " + fault.host + " is not a network namespace of this run");
  }
  const std::string peer = fault.kind == LinkFault::Kind::kPartition ? address(fault.peer) : "";
  return linkCommands(fault, namespaces_.at(fault.host), link->second, peer);
}

void HostNetwork::applyLinkFault(const LinkFault& fault) const
{
  for (const auto& argv : commandsFor(fault).apply) {
    process::runChecked(argv);
  }
}

void HostNetwork::healLinkFault(const LinkFault& fault) const
{
  std::optional<std::runtime_error> first;
  for (const auto& argv : commandsFor(fault).heal) {
    try {
      process::runChecked(argv);
    } catch (const std::runtime_error& e) {
      if (!first) {
        first = e;
      }
    }
  }
  if (first) {
    throw *first;
  }
}

std::vector<std::string> HostNetwork::interfaces(const std::string& host) const
{
  const auto it = std::find_if(manifest_.hosts.begin(), manifest_.hosts.end(),
                               [&](const Host& h) { return host.empty() ? h.kind == HostKind::kLocal : h.name == host; });
  if (it == manifest_.hosts.end()) {
    return {manifest_.usesNamespaces() ? manifest_.subnet + ".1" : "127.0.0.1"};
  }
  return it->interfaces.empty() ? std::vector<std::string>{address(it->name)} : it->interfaces;
}

std::vector<std::string> HostNetwork::onHost(const Host& host, std::vector<std::string> argv) const
{
  return host.kind == HostKind::kNetns || host.kind == HostKind::kSsh ? command(host, std::move(argv), {}) : argv;
}

void HostNetwork::installFirewall(int domain, const std::vector<int>& extra_ports)
{
  // Every address a manifest host may send from (the run's and the ones it names), and the
  // launcher's own side (its observer and recorder).
  std::vector<std::string> admitted = interfaces("");
  for (const auto& h : manifest_.hosts) {
    admitted.push_back(address(h.name));
    admitted.insert(admitted.end(), h.interfaces.begin(), h.interfaces.end());
  }
  std::sort(admitted.begin(), admitted.end());
  admitted.erase(std::unique(admitted.begin(), admitted.end()), admitted.end());
  for (const auto& h : manifest_.hosts) {
    if (h.kind == HostKind::kLocal) {
      continue;
    }
    const FirewallRules rules = firewallRules("QUAD-" + run_id_, ddsPorts(domain), extra_ports, admitted);
    for (const auto& argv : rules.install) {
      try {
        process::runChecked(onHost(h, argv));
      } catch (const std::runtime_error& e) {
        throw std::runtime_error("firewall on host " + h.name + ": " + e.what());
      }
    }
    if (h.kind == HostKind::kSsh) {
      for (const auto& argv : rules.remove) {
        firewall_removal_.push_back(onHost(h, argv));
      }
    }
  }
}

std::string HostNetwork::namespaceOf(const std::string& host) const
{
  const auto it = namespaces_.find(host);
  return it == namespaces_.end() ? "" : it->second;
}

std::vector<std::string> HostNetwork::command(const Host& host, std::vector<std::string> argv,
                                              const std::map<std::string, std::string>& env) const
{
  switch (host.kind) {
    case HostKind::kLocal:
      return argv;
    case HostKind::kNetns: {
      std::vector<std::string> out{"ip", "netns", "exec", namespaceOf(host.name)};
      out.insert(out.end(), argv.begin(), argv.end());
      return out;
    }
    case HostKind::kSsh: {
      // The remote checkout may sit elsewhere: paths under this one move to host.root.
      const std::string here = manifest_.file.parent_path().parent_path().string();
      auto remote = [&](std::string s) {
        if (!host.root.empty() && s.starts_with(here)) {
          s = host.root + s.substr(here.size());
        }
        return s;
      };
      // -tt: a terminal on the far side, so that closing the connection hangs the module up.
      std::vector<std::string> out{"ssh", "-tt", "-o", "BatchMode=yes", "-p", std::to_string(host.ssh_port)};
      out.insert(out.end(), host.ssh_options.begin(), host.ssh_options.end());
      out.insert(out.end(), {host.address, "--", "env"});
      for (const auto& [k, v] : env) {
        out.push_back(process::shellQuote(k + "=" + remote(v)));
      }
      for (auto& a : argv) {
        out.push_back(process::shellQuote(remote(a)));
      }
      return out;
    }
  }
  return argv;
}

}  // namespace quad::launch
