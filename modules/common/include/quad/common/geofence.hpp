// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The keep-in volume: an axis-aligned box in the world frame that the vehicle's centre must
/// stay in. A run's manifest gives it once (`geofence: {min: [x, y, z], max: [x, y, z]}`);
/// the launcher hands it to the modules that act on it, each of which reads it with this
/// table: the planner plans only inside it, the controller holds and returns when the
/// vehicle is pushed out. Without one, the box is unbounded.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "quad/common/param_table.hpp"
#include "quad/common/yaml_input.hpp"

namespace quad::common {

struct Geofence {
  static constexpr double kUnbounded = 1e6;  ///< [m] no fence: every coordinate is inside
  std::array<double, 3> min{-kUnbounded, -kUnbounded, -kUnbounded};  ///< [m]
  std::array<double, 3> max{kUnbounded, kUnbounded, kUnbounded};     ///< [m]

  bool bounded() const;
  /// `p`: anything with p[0], p[1], p[2] (an Eigen vector, std::array).
  template <typename P>
  bool contains(const P& p) const
  {
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (!(p[i] >= min[k] && p[i] <= max[k])) {
        return false;
      }
    }
    return true;
  }
};

/// `geofence.min` and `geofence.max`, for a module's own table to include.
const ParamTable<Geofence>& geofenceTable();

/// Throws ConfigError naming `origin` and the key when a minimum is not below its maximum.
void checkGeofence(const Geofence& fence, std::string_view origin);

/// `{min: [x, y, z], max: [x, y, z]}` under `key` of a file (a manifest, a scenario), each
/// minimum below its maximum; nothing when absent, or when wrong (then `r` has the problem).
std::optional<Geofence> readGeofence(const YAML::Node& node, const std::string& key, YamlReader& r);

/// The `--set` pairs that hand `fence` to a module whose table includes geofenceTable().
std::vector<std::pair<std::string, std::string>> geofenceSets(const Geofence& fence);

}  // namespace quad::common
