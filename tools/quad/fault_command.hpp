// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad fault SCENARIO`: launches a scenario's manifest, applies its faults on its timeline,
/// checks the stack's reactions and the run's outcome, and prints a pass/fail table.

#include "quad/fault/run.hpp"

namespace quad::tools {

/// 0: every check passed; 1: some failed; 2: the scenario or its manifest is invalid.
int fault(const fault::FaultOptions& options);

}  // namespace quad::tools
