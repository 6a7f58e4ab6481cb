// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad security init`.

#include <string>
#include <vector>

#include "quad/security/roles.hpp"

namespace quad::tools {

/// The identities of quad's modules and tools, and one per container in `containers` (each its
/// modules' names joined by commas, as its manifest lists them: "plant,estimation,control").
/// Prints the files written; returns the exit status.
int securityInit(const security::InitOptions& options, const std::vector<std::string>& containers);

}  // namespace quad::tools
