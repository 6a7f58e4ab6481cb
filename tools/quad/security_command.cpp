// SPDX-License-Identifier: BSD-3-Clause
#include "security_command.hpp"

#include <cstdio>
#include <stdexcept>

#include "quad/common/name_list.hpp"

namespace quad::tools {

int securityInit(const security::InitOptions& options, const std::vector<std::string>& containers)
{
  auto roles = security::quadRoles();
  for (const auto& list : containers) {
    try {
      roles.push_back(security::containerRole(common::nameList(list)));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--container " + list + ": " + e.what());
    }
  }
  const auto written = security::init(options, roles);
  for (const auto& f : written) {
    std::printf("%s\n", f.string().c_str());
  }
  std::printf("security: %zu identities in %s; set QUAD_SECURITY_DIR (or a manifest's security key) to it\n",
              roles.size(), options.dir.string().c_str());
  return 0;
}

}  // namespace quad::tools
