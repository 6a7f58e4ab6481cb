// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Control core types ⇄ messages. Only the node includes generated types.

#include <vector>

#include <quad/msg/ControlReference.h>
#include <quad/msg/ControlStatus.h>
#include <quad/msg/Path.h>
#include <quad/msg/VehicleCommand.h>
#include "quad/runtime/state_input.hpp"

#include "quad/control/flight_controller.hpp"

namespace quad::control {

VehicleState fromSample(const runtime::StateSample& s);
std::vector<Vector3> waypointsOf(const msg::Path& m);
/// What a planner status means to the controller: fly, hold, or give the goal up.
PathKind pathKind(msg::PlanStatus status);
Command fromMessage(msg::CommandKind kind);
msg::ControlMode toMessage(Mode mode);
msg::FailsafeReason toMessage(Reason reason);
msg::ControlReference toMessage(const Reference& r, double progress);

}  // namespace quad::control
