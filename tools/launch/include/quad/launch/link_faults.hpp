// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Faults on the link of a network-namespace host (the launcher made the namespace, so it
/// can break it): random packet loss, a partition from another host, the link down. Here
/// only the commands that apply and undo each; HostNetwork runs them.

#include <string>
#include <vector>

namespace quad::launch {

/// The route a namespace needs to send multicast (DDS discovery) on its link.
inline constexpr const char* kMulticastRoute = "224.0.0.0/4";

struct LinkFault {
  enum class Kind {
    kLoss,       ///< each packet in or out of the host's link dropped with `probability`
    kPartition,  ///< nothing between the host and `peer` either way
    kDown,       ///< the host's link down (`ip link set down`), up again when healed
  };
  Kind kind = Kind::kLoss;
  std::string host;        ///< a netns host
  double probability = 0;  ///< kLoss, in (0, 1]
  std::string peer;        ///< kPartition: another host of the run

  /// "loss 0.2 on flight's link", "partition flight | brain", "flight's link down"
  std::string describe() const;
};

/// Command lines (argv, run as root) for one fault.
struct LinkCommands {
  std::vector<std::vector<std::string>> apply;
  std::vector<std::vector<std::string>> heal;  ///< undo `apply`, in order
};

/// The commands for `fault` on namespace `ns`, whose end of the host's link is `link`;
/// `peer_address` is the partition peer's address. The rules match the link only, so
/// traffic between modules of the same host is untouched.
LinkCommands linkCommands(const LinkFault& fault, const std::string& ns, const std::string& link,
                          const std::string& peer_address);

}  // namespace quad::launch
