#pragma once
/// @file
/// Plant core types ⇄ messages. Only the node includes generated types.

#include <optional>
#include <string>

#include <quad/msg/FaultCommand.h>
#include <quad/msg/Imu.h>
#include <quad/msg/PointCloud.h>
#include <quad/msg/SimEvent.h>
#include <quad/msg/VehicleState.h>

#include "quad/plant/simulation.hpp"

namespace quad::plant {

msg::VehicleState toMessage(const StateSample& s);
msg::Imu toMessage(const ImuReading& r);
msg::PointCloud toMessage(const DepthReading& r, double max_range);
msg::SimEvent toMessage(const SimEventRecord& e);

/// A fault command for the plant as a core Fault starting at `now_ns`; when the command asks
/// for something the plant does not apply, `why_not` says why and nothing is returned.
std::optional<Fault> faultFrom(const msg::FaultCommand& command, std::int64_t now_ns, std::string& why_not);

/// The command that asks the plant node for `fault` (faultFrom's inverse, start aside: the
/// plant applies a command when it arrives).
msg::FaultCommand toCommand(const Fault& fault);

}  // namespace quad::plant
