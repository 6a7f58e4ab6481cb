// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/identity.hpp"

namespace quad::common {

SecurityFiles securityFiles(const std::filesystem::path& dir, const std::string& identity)
{
  return SecurityFiles{dir / "ca.pem", dir / (identity + ".pem"), dir / (identity + ".key"), dir / "governance.p7s",
                       dir / (identity + ".permissions.p7s")};
}

std::string securityIdentity(std::string_view participant_name)
{
  std::string_view name = participant_name;
  if (name.starts_with("quad_")) {
    name.remove_prefix(5);
  }
  if (name.starts_with("topic_") && name != "topic_pub") {
    return "topic";
  }
  return std::string(name);
}

std::string containerName(const std::vector<std::string>& modules)
{
  std::string name;
  for (const auto& m : modules) {
    name += (name.empty() ? "" : "+") + m;
  }
  return name;
}

}  // namespace quad::common
