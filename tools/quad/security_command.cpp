// SPDX-License-Identifier: BSD-3-Clause
#include "security_command.hpp"

#include <cstdio>

namespace quad::tools {

int securityInit(const security::InitOptions& options)
{
  const auto roles = security::quadRoles();
  const auto written = security::init(options, roles);
  for (const auto& f : written) {
    std::printf("%s\n", f.string().c_str());
  }
  std::printf("security: %zu identities in %s; set QUAD_SECURITY_DIR (or a manifest's security key) to it\n",
              roles.size(), options.dir.string().c_str());
  return 0;
}

}  // namespace quad::tools
