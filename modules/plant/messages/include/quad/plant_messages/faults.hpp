// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Plant faults as quad/system/fault commands, both ways: the plant node applies what a
/// command asks, and the fault tool writes the command for a scenario's plant fault. A
/// library of its own so that the tool does not reach into the plant's node.

#include <cstdint>
#include <optional>
#include <string>

#include <quad/msg/FaultCommand.h>

#include "quad/plant/faults.hpp"

namespace quad::plant {

/// A fault command for the plant as a core Fault starting at `now_ns`; when the command asks
/// for something the plant does not apply, `why_not` says why and nothing is returned.
std::optional<Fault> faultFrom(const msg::FaultCommand& command, std::int64_t now_ns, std::string& why_not);

/// The command that asks the plant node for `fault` (faultFrom's inverse, start aside: the
/// plant applies a command when it arrives).
msg::FaultCommand toCommand(const Fault& fault);

}  // namespace quad::plant
