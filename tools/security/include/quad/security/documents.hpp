// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// DDS Security's governance and permissions documents (OMG DDS Security 1.1, 9.4.1): what
/// quad's domains require of every participant, and what each identity may publish and
/// subscribe. Plain XML text; pki.hpp signs it.

#include <string>
#include <vector>

#include "quad/security/pki.hpp"

namespace quad::security {

/// Governance for domains 0..232: unauthenticated participants refused, joining controlled
/// by permissions, discovery, liveliness and every topic's submessages and payloads
/// encrypted, reading and writing controlled per topic.
std::string governanceXml();

/// What one identity may do. Topic names are fnmatch patterns ("*": every topic).
struct Grant {
  std::string identity;              ///< "plant", "record", ...
  std::string subject;               ///< its certificate's subject, RFC 2253
  std::vector<std::string> publish;  ///< empty: publishes nothing
  std::vector<std::string> subscribe;
  Clock::time_point not_before;
  Clock::time_point not_after;
};

/// Permissions with one grant; anything the grant does not allow is denied.
std::string permissionsXml(const Grant& grant);

}  // namespace quad::security
