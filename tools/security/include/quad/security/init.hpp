// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad security init`: one folder with everything DDS Security needs for a quad domain.

#include <filesystem>
#include <string>
#include <vector>

#include "quad/security/documents.hpp"

namespace quad::security {

/// What one identity may publish and subscribe (fnmatch patterns).
struct Role {
  std::string identity;
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
};

struct InitOptions {
  std::filesystem::path dir;
  int days = 365;      ///< validity of identities and permissions; the CA gets ten times that
  bool force = false;  ///< replace an existing authority (every identity it signed stops working)
};

/// Creates, in `options.dir` (mode 0700): ca.pem and ca.key (the identity and permissions
/// authority), governance.xml and its signed governance.p7s, and per role <identity>.pem,
/// <identity>.key (0600), <identity>.permissions.xml and <identity>.permissions.p7s. An
/// existing authority is kept (its identities are reissued) unless `force`. Throws
/// std::runtime_error naming the file on any failure. Returns the files written.
std::vector<std::filesystem::path> init(const InitOptions& options, const std::vector<Role>& roles);

}  // namespace quad::security
