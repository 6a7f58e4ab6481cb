#pragma once
/// @file
/// The control node's parameters (configs/control.yaml): declared once, here.

#include <filesystem>

#include "quad/common/params.hpp"
#include "quad/control/flight_controller.hpp"

namespace quad::control {

struct ControlNodeConfig {
  std::filesystem::path vehicle_file;
  FlightControllerConfig flight;
  bool autostart = false;     ///< arm and take off by itself once the state is fresh
  double status_rate = 20.0;  ///< [Hz]
};

common::ParamSchema controlSchema();
ControlNodeConfig controlConfigFrom(const common::Params& params);

}  // namespace quad::control
