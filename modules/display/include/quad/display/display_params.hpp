// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The display participant's parameters (configs/display.yaml), declared once.

#include <filesystem>

#include "quad/common/param_table.hpp"
#include "quad/display/trace.hpp"

namespace quad::display {

struct DisplayParams {
  std::filesystem::path world_file;  ///< the world whose obstacles are drawn; empty: none
  double transforms_rate = 30.0;     ///< [Hz] of sim time
  double trajectory_rate = 2.0;      ///< [Hz] of sim time
  double map_rate = 1.0;             ///< [Hz] of sim time, at most
  double goal_radius = 0.3;          ///< [m] of the goal's sphere
  TraceParams trace;
};

const common::ParamTable<DisplayParams>& displayTable();

}  // namespace quad::display
