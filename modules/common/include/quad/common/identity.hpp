// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What a participant is called and who it is to DDS Security: the name of a container of
/// modules, which identity a participant of a given name uses, and where it finds that
/// identity's files (made by `quad security init`). No DDS: the launcher checks a manifest
/// against the same rules.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace quad::common {

struct SecurityFiles {
  std::filesystem::path ca;           ///< identity and permissions authority (ca.pem)
  std::filesystem::path certificate;  ///< <identity>.pem
  std::filesystem::path key;          ///< <identity>.key, readable by its owner only
  std::filesystem::path governance;   ///< governance.p7s, signed by the authority
  std::filesystem::path permissions;  ///< <identity>.permissions.p7s, signed by the authority
};

SecurityFiles securityFiles(const std::filesystem::path& dir, const std::string& identity);

/// The identity of a participant: its name without "quad_" ("quad_record" -> "record"), the
/// read-only topic tools sharing "topic" ("quad_topic_echo" -> "topic"; "quad_topic_pub"
/// publishes and keeps its own).
std::string securityIdentity(std::string_view participant_name);

/// The name of a container of these modules: "plant+estimation+control". Its participant's
/// name, its log's, and the default DDS Security identity (securityIdentity()) are this one.
std::string containerName(const std::vector<std::string>& modules);

}  // namespace quad::common
