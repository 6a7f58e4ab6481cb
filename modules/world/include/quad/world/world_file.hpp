// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// World files (YAML): bounds, start, goal, obstacles and seeded generators.
///
/// ```yaml
/// bounds: {min: [-5, -10, 0], max: [60, 10, 10]}     # m, ENU
/// start: [0, 0, 0]
/// goal:  [50, 0, 2]
/// obstacles:
///   - {type: box, center: [10, 1, 2], size: [2, 2, 4], yaw: 0.3}
///   - {type: cylinder, center: [20, -2], radius: 0.4, height: 8}   # vertical, base at z = 0
///   - {type: sphere, center: [30, 0, 3], radius: 1.2}
/// generators:
///   - {type: forest, seed: 7, min: [5, -8], max: [45, 8], density: 0.05,
///      radius: [0.2, 0.6], height: [5, 9]}
///   - {type: walls, seed: 3, min: [12, -10], max: [40, 10], count: 3, gap: 2.5,
///      thickness: 0.3, height: 8}
/// maps:                                               # real scans (scan_file.hpp)
///   - {file: scans/office.bt, pose: [0, 0, 0, 0], resolution: 0.1}   # x, y, z [m], yaw [rad]
/// ```
///
/// A map's file is found relative to the world file. `resolution` defaults to an OctoMap's own
/// and is required for a point cloud. Without `bounds`, the world's bounds are the maps' box.
/// Obstacles are numbered in file order, generated ones after the listed ones, in generator
/// order. Generators keep `clearance` (default 2 m) free around start and goal. The same
/// file and seeds give the same world, bit for bit.

#include <filesystem>
#include <string_view>

#include "quad/world/world.hpp"

namespace quad::world {

/// Parses and validates world YAML. Every problem is reported at once, as
/// `origin:key: value: reason` lines of a common::ConfigError. Map files are found relative
/// to `base_dir`.
World parseWorld(std::string_view yaml_text, std::string_view origin, const std::filesystem::path& base_dir);
/// The same with map files relative to the folder of `origin` taken as a path.
World parseWorld(std::string_view yaml_text, std::string_view origin);

/// Reads a world file; an unreadable file is a ConfigError naming it.
World loadWorld(const std::filesystem::path& file);

}  // namespace quad::world
