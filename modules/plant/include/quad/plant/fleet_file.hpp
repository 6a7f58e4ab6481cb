// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A fleet file: the vehicles one plant simulates in its world, e.g.
///
///     vehicles:
///       - {id: 1, start: [0, 0, 0], goal: [40, 5, 2]}
///       - {id: 2, start: [0, 6, 0], vehicle: vehicles/x500.yaml, faults: faults.yaml}
///
/// `id` is the vehicle's id (Header.vehicle_id, QUAD_VEHICLE_ID of its modules), unique in the
/// file; `start` and `goal` [m] lie in the world's bounds (`goal` defaults to the world's);
/// `vehicle` defaults to the plant's vehicle file, and `faults` (a fault schedule for that
/// vehicle alone) to none; both resolve against the fleet file's folder. Every problem is
/// reported as `file:key: value: reason` in a common::ConfigError.

#include <filesystem>
#include <string_view>
#include <vector>

#include "quad/plant/fleet.hpp"

namespace quad::plant {

std::vector<FleetVehicle> parseFleet(std::string_view yaml_text, std::string_view origin,
                                     const std::filesystem::path& folder, const world::World& world,
                                     const std::filesystem::path& default_vehicle);
std::vector<FleetVehicle> loadFleet(const std::filesystem::path& file, const world::World& world,
                                    const std::filesystem::path& default_vehicle);

}  // namespace quad::plant
