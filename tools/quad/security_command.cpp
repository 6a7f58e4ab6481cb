// SPDX-License-Identifier: BSD-3-Clause
#include "security_command.hpp"

#include <cstdio>
#include <stdexcept>

namespace quad::tools {

int securityInit(const security::InitOptions& options, const std::vector<std::string>& containers)
{
  auto roles = security::quadRoles();
  for (const auto& list : containers) {
    std::vector<std::string> modules;
    for (std::size_t from = 0;;) {
      const std::size_t comma = list.find(',', from);
      modules.push_back(list.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
      if (comma == std::string::npos) {
        break;
      }
      from = comma + 1;
    }
    try {
      roles.push_back(security::containerRole(modules));
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
