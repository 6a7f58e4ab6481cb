// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad launch MANIFEST`: starts a manifest's modules on their hosts, supervises them, and
/// flies its mission when it has one.

#include "quad/launch/run.hpp"

namespace quad::tools {

int launch(const launch::LaunchOptions& options);

}  // namespace quad::tools
