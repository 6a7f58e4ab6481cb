// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad security init`.

#include "quad/security/roles.hpp"

namespace quad::tools {

/// Prints the files written; returns the exit status.
int securityInit(const security::InitOptions& options);

}  // namespace quad::tools
