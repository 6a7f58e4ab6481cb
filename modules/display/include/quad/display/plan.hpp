// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The trajectory the controller flies, as a viewer draws it: poses along it at equal times,
/// each facing where the trajectory heads there.

#include <vector>

#include "quad/display/trace.hpp"
#include "quad/trajectory/trajectory.hpp"

namespace quad::display {

/// Poses of `t` every `period` [s] from its start to its end (the end included), stamped at
/// their sim times; at rest, a pose keeps the heading of the one before (level, along +x at
/// first).
std::vector<TracePose> planPoses(const trajectory::Trajectory& t, double period);

}  // namespace quad::display
