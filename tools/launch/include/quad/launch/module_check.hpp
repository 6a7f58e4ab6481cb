// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad launch --check`: every module's parameters (its config, the manifest's `set` and the
/// command line's) checked by the module's own program against its own schema, as it would
/// start, without starting anything.

#include <string>
#include <vector>

#include "quad/launch/manifest.hpp"

namespace quad::launch {

/// Runs each quad module's process of the manifest (a container with all its modules) with
/// `--check`; the problems it reports, each line prefixed with the process's name. Modules on
/// ssh hosts (their programs are on those machines) and programs that are not quad modules are
/// not checked. Empty: every parameter is valid.
std::vector<std::string> checkModuleParameters(const Manifest& manifest);

}  // namespace quad::launch
