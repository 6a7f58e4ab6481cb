// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Plant core types ⇄ messages. Only the node includes generated types.

#include <optional>
#include <string>

#include <quad/msg/BaroAltitude.h>
#include <quad/msg/BatteryState.h>
#include <quad/msg/Imu.h>
#include <quad/msg/MagneticField.h>
#include <quad/msg/PointCloud.h>
#include <quad/msg/PositionFix.h>
#include <quad/msg/Range.h>
#include <quad/msg/SimEvent.h>
#include <quad/msg/VehicleState.h>

#include "quad/plant/simulation.hpp"
#include "quad/plant_messages/faults.hpp"

namespace quad::plant {

msg::VehicleState toMessage(const StateSample& s);
msg::Imu toMessage(const ImuReading& r);
msg::PositionFix toMessage(const PositionReading& r);
msg::BaroAltitude toMessage(const BaroReading& r);
msg::Range toMessage(const RangeReading& r);
msg::MagneticField toMessage(const MagReading& r);
msg::BatteryState toMessage(const BatteryReading& r);
msg::PointCloud toMessage(const DepthReading& r, double max_range);
msg::SimEvent toMessage(const SimEventRecord& e);

}  // namespace quad::plant
