// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The plant node's parameters (configs/plant.yaml): declared once, here.

#include <filesystem>
#include <string>
#include <vector>

#include "quad/common/param_table.hpp"
#include "quad/plant/simulation.hpp"
#include "quad/runtime/state_input.hpp"

namespace quad::plant {

struct PlantNodeConfig {
  enum class Mode { kRealTime, kLockstep };
  Mode mode = Mode::kRealTime;
  double real_time_factor = 1.0;
  double duration_s = 0.0;                      ///< stop after this much sim time; 0 = never
  std::vector<std::string> lockstep_participants;
  bool lockstep_wait_for_command = true;
  double lockstep_timeout_s = 5.0;              ///< [s] wall time before a lockstep wait is reported
  std::int64_t lockstep_period_ns = 4'000'000;  ///< sim time between lockstep rounds
  /// What the stack flies on. In lockstep the controller answers it: the true state, or the
  /// estimate the estimator makes of each IMU sample; the round waits for that answer.
  runtime::StateSource state_source = runtime::StateSource::kEstimate;
  std::filesystem::path vehicle_file = "vehicles/x500.yaml";
  std::filesystem::path world_file = "worlds/demo.yaml";
  std::filesystem::path fault_schedule_file;    ///< empty: none
  /// The vehicles simulated (plant/fleet_file.hpp); empty: one, the participant's vehicle
  /// (QUAD_VEHICLE_ID) at the world's start, with `vehicle_file` and the fault schedule.
  std::filesystem::path fleet_file;
  SimulationConfig simulation;
};

/// configs/plant.yaml: each key with its unit, range and the field it fills; the defaults are
/// PlantNodeConfig's own.
const common::ParamTable<PlantNodeConfig>& plantTable();
common::ParamSchema plantSchema();

/// Relative file paths resolve against the directory of the config file (or configs/ for
/// the defaults). Throws common::ConfigError on contradictions (e.g. a lockstep period that
/// is not a whole number of steps).
PlantNodeConfig plantConfigFrom(const common::Params& params);

}  // namespace quad::plant
