// SPDX-License-Identifier: BSD-3-Clause
#include "quad/security/init.hpp"

#include <stdexcept>

#include "quad/common/identity.hpp"

namespace quad::security {

namespace fs = std::filesystem;

namespace {

constexpr auto kPublic = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                         fs::perms::others_read;

}  // namespace

std::vector<fs::path> init(const InitOptions& options, const std::vector<Role>& roles)
{
  if (options.days < 1 || options.days > 3650) {
    throw std::invalid_argument("--days " + std::to_string(options.days) + ": expected 1 to 3650");
  }
  std::error_code ec;
  fs::create_directories(options.dir, ec);
  if (ec) {
    throw std::runtime_error("cannot create " + options.dir.string() + ": " + ec.message());
  }
  fs::permissions(options.dir, fs::perms::owner_all, ec);
  if (ec) {
    throw std::runtime_error("cannot restrict " + options.dir.string() + " to its owner: " + ec.message());
  }
  std::vector<fs::path> written;
  const auto now = Clock::now();
  const auto not_before = now - std::chrono::hours(1);  // clocks of other hosts may be a little behind
  const auto not_after = now + std::chrono::hours(24) * options.days;
  const fs::path ca_cert = options.dir / "ca.pem";
  const fs::path ca_key = options.dir / "ca.key";
  KeyPair ca;
  if (fs::exists(ca_key) && !options.force) {
    ca = KeyPair::load(ca_cert, ca_key);
  } else {
    ca = KeyPair::makeAuthority("quad CA", not_before, now + std::chrono::hours(24) * 10 * options.days);
    ca.save(ca_cert, ca_key);
    written.insert(written.end(), {ca_cert, ca_key});
  }
  const std::string governance = governanceXml();
  writeFile(options.dir / "governance.xml", governance, kPublic);
  writeFile(options.dir / "governance.p7s", ca.signSmime(governance), kPublic);
  written.insert(written.end(), {options.dir / "governance.xml", options.dir / "governance.p7s"});
  for (const auto& role : roles) {
    const common::SecurityFiles files = common::securityFiles(options.dir, role.identity);
    const KeyPair identity = KeyPair::makeIdentity(ca, role.identity, not_before, not_after);
    identity.save(files.certificate, files.key);
    const std::string permissions = permissionsXml(
        Grant{role.identity, identity.subject(), role.publish, role.subscribe, not_before, not_after});
    const fs::path xml = options.dir / (role.identity + ".permissions.xml");
    writeFile(xml, permissions, kPublic);
    writeFile(files.permissions, ca.signSmime(permissions), kPublic);
    written.insert(written.end(), {files.certificate, files.key, xml, files.permissions});
  }
  return written;
}

}  // namespace quad::security
