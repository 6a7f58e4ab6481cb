// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Where a participant finds its DDS Security files (made by `quad security init`), and which
/// identity a participant of a given name uses.

#include <filesystem>
#include <string>
#include <string_view>

namespace quad::dds {

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

}  // namespace quad::dds
