// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Datagram faults as quad/system/fault commands: what the fault tool sends and what a
/// node's fault layer applies (plant faults have their own, in the plant node).

#include <optional>
#include <string>

#include <quad/msg/FaultCommand.h>

#include "quad/wire/datagram_faults.hpp"

namespace quad::dds {

/// FAULT_DATAGRAM_LOSS ... FAULT_DATAGRAM_CORRUPT.
bool isDatagramFault(msg::FaultKind kind);

/// The command that asks `module`'s fault layer to apply `fault` (target: the sender's name).
msg::FaultCommand toCommand(const wire::DatagramFault& fault, const std::string& module);

/// The fault a command asks for; nullopt with `why_not` set when it cannot be applied.
std::optional<wire::DatagramFault> datagramFaultFrom(const msg::FaultCommand& command, std::string& why_not);

}  // namespace quad::dds
