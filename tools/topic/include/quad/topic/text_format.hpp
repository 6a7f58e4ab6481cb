// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Text forms of samples for the command line: YAML-like printing, and values typed by the
/// user (YAML, flow or block) read into JSON.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace quad::topic {

/// Prints a decoded sample as indented `key: value` lines, the way `ros2 topic echo` does.
std::string toYaml(const nlohmann::ordered_json& value);

/// Parses YAML text ("{kind: COMMAND_HOLD, altitude: 2}") into JSON. Plain scalars become
/// booleans, integers or numbers where they read as one (.nan, .inf and -.inf included);
/// quoted scalars stay strings.
/// Throws std::invalid_argument with the YAML error's line and column.
nlohmann::ordered_json yamlToJson(std::string_view text);

}  // namespace quad::topic
