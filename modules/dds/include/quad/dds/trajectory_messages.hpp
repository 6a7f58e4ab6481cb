// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad::trajectory's Trajectory ⇄ the IDL's (quad/control/trajectory): the controller writes
/// what it flies, the display and the tools read it back into the core's, to sample it.

#include <optional>
#include <string>

#include <quad/msg/Trajectory.h>

#include "quad/trajectory/trajectory.hpp"

namespace quad::dds {

/// The message of a trajectory (its header's stamp and seq left to the writer). Pieces past the
/// IDL's bound are left out: a trajectory that long is cut there.
msg::Trajectory toMessage(const trajectory::Trajectory& t, std::uint32_t count, std::uint32_t path_version);

/// The trajectory a message carries; nullopt, with `why` said, when it has no piece, a
/// duration is not positive or a value not finite.
std::optional<trajectory::Trajectory> fromMessage(const msg::Trajectory& m, std::string* why = nullptr);

}  // namespace quad::dds
