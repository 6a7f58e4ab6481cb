// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad command VERB`: the operator's command line to a running stack. Each command is
/// answered (quad/control/command_ack, quad/planning/goal_ack): taken, or refused and why.

#include <string>
#include <vector>

#include "quad/topic/connection.hpp"

namespace quad::tools {

struct CommandOptions {
  topic::ConnectionOptions connection;
  double timeout_s = 10.0;       ///< for the peers to be found and to answer
  std::string verb;              ///< arm, disarm, takeoff, hold, land, return, goal, goto
  double altitude = 0.0;         ///< takeoff: [m] above the take-off point; 0: the controller's altitude
  std::vector<double> position;  ///< goal, goto: x y z [m], world frame (goto without one: the goal set)
  double tolerance = 0.3;        ///< goal, goto: [m] reached within this distance
};

/// 0 when taken, 1 when refused, 2 for bad input (named), 3 when no answer came in time.
int command(const CommandOptions& options);

}  // namespace quad::tools
