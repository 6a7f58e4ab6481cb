// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The control node's parameters (configs/control.yaml): declared once, here.

#include <filesystem>

#include "quad/common/param_table.hpp"
#include "quad/control/flight_controller.hpp"
#include "quad/runtime/state_input.hpp"

namespace quad::control {

/// The controller as configs/control.yaml's defaults fly it: gains tuned for the x500 (the
/// core's own defaults are Lee et al.'s, for their vehicle) and the staleness timeouts of the
/// quad/sim/state and quad/planning/path contracts.
FlightControllerConfig nodeFlightDefaults();

struct ControlNodeConfig {
  std::filesystem::path vehicle_file = "vehicles/x500.yaml";
  FlightControllerConfig flight = nodeFlightDefaults();
  runtime::StateSource state_source = runtime::StateSource::kEstimate;
  bool autostart = false;     ///< arm and take off by itself once the state is fresh
  double status_rate = 20.0;  ///< [Hz]
};

/// configs/control.yaml: each key with its unit, range and the field it fills; the defaults
/// are ControlNodeConfig's own.
const common::ParamTable<ControlNodeConfig>& controlTable();
common::ParamSchema controlSchema();
ControlNodeConfig controlConfigFrom(const common::Params& params);

}  // namespace quad::control
