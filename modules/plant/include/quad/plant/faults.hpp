// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Faults the plant applies to itself: rotor failure or degradation, sensor dropout, stuck
/// sensor, extra sensor noise, wind gusts, a push, battery cells failing. Each has an id, a start and a duration in sim time;
/// the simulation reports when each takes effect and when it clears.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "quad/common/yaml_input.hpp"
#include "quad/geometry/so3.hpp"

namespace quad::plant {

enum class Sensor { kDepth, kImu, kState, kPosition, kBaro, kMag, kRange, kRangeUp };

std::string_view toString(Sensor s);
std::optional<Sensor> parseSensor(std::string_view text);
/// Every sensor's name, for messages: "depth, imu, ... or mag".
std::string sensorNames();

struct Fault {
  enum class Kind { kMotor, kSensorDropout, kSensorStuck, kSensorNoise, kSensorOffset, kWindGust, kPush, kCellLoss };
  std::uint32_t id = 0;
  Kind kind = Kind::kMotor;
  int rotor = 0;                         ///< kMotor: 0..3
  double magnitude = 0.0;                ///< kMotor: remaining efficiency [0, 1];
                                         ///< kSensorNoise: extra std dev (SI units)
  Sensor sensor = Sensor::kDepth;        ///< sensor faults
  geometry::Vector3 wind_W = geometry::Vector3::Zero();  ///< kWindGust [m/s]
  geometry::Vector3 force_W = geometry::Vector3::Zero(); ///< kPush [N] on the vehicle
  /// kSensorOffset: added to the sensor's readings: position [m, world] (a jump), baro
  /// [m] (z only), mag [µT, world] (a disturbance), imu [m/s², body] (an accelerometer bias step),
  /// range [m] (z only: a reading that far off)
  geometry::Vector3 offset = geometry::Vector3::Zero();
  int cells = 0;                         ///< kCellLoss: battery cells that fail short (for good)
  std::int64_t start_ns = 0;             ///< sim time it takes effect
  std::int64_t duration_ns = 0;          ///< <= 0: until cleared

  std::string describe() const;
};

std::string_view toString(Fault::Kind k);

/// One fault from a YAML map: `kind` and that kind's keys (rotor, efficiency; sensor;
/// std_dev; wind) and `duration` [s] (0 or absent: until cleared), as a schedule entry has
/// them; `extra_keys` are keys the caller reads itself. Problems go to `reader` under `key`.
/// The id and start are the caller's to set.
std::optional<Fault> parseFault(common::YamlReader& reader, YAML::Node node, const std::string& key,
                                const std::set<std::string>& extra_keys);

/// A schedule file: a YAML list of faults, e.g.
/// `- {id: 1, kind: motor, rotor: 2, efficiency: 0.5, at: 10.0, duration: 5.0}`
/// (kinds: motor, sensor_dropout, sensor_stuck, sensor_noise, sensor_offset, wind_gust, push, cell_loss;
/// times in seconds).
/// Every problem is reported as `file:key: value: reason` in a common::ConfigError.
std::vector<Fault> parseFaultSchedule(std::string_view yaml_text, std::string_view origin);
std::vector<Fault> loadFaultSchedule(const std::filesystem::path& file);

}  // namespace quad::plant
