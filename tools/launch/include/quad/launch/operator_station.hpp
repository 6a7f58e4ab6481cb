// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The operator's station as a command line uses it (`quad command`): sends one command or
/// goal to a running stack and waits for its answer, the controller's on
/// quad/control/command_ack, the planner's on quad/planning/goal_ack and then the first path
/// to the goal.

#include <memory>
#include <string>

#include <Eigen/Core>

#include "quad/dds/participant.hpp"

namespace quad::launch {

/// What the operator asks of the controller (quad/system/command).
enum class OperatorCommand { kArm, kDisarm, kTakeoff, kStartMission, kHold, kLand, kReturn };

struct OperatorAnswer {
  enum class Outcome { kTaken, kRefused, kNoAnswer };
  Outcome outcome = Outcome::kNoAnswer;
  std::string text;  ///< the answer in words: the answerer's reason, or what was not heard
  std::string mode;  ///< the controller's mode once it answered a command ("HOVER"); else empty
};

class OperatorStation {
public:
  /// Every wait for a peer and an answer ends `timeout_s` [s] after the command was given.
  OperatorStation(dds::ParticipantOptions options, double timeout_s);
  ~OperatorStation();

  /// The controller's mode, from its latched status ("DISARMED"); empty when none was heard.
  std::string mode();
  /// Sends `command` (a take-off `takeoff_altitude` [m] up; 0: the controller's configured
  /// altitude) and waits for the controller's answer.
  OperatorAnswer command(OperatorCommand command, double takeoff_altitude = 0.0);
  /// Gives a new goal (the next goal id) at `p_W` [m], reached within `tolerance` [m], and
  /// waits for the planner's answer and, once taken, its first path to it: a path is taken; the
  /// planner's word that none exists (sealed off, in an obstacle) refuses it. Throws
  /// std::invalid_argument, naming the value, for a position that is not finite or a
  /// tolerance that is not positive.
  OperatorAnswer setGoal(const Eigen::Vector3d& p_W, double tolerance);

private:
  struct Endpoints;
  struct GoalEndpoints;
  std::int64_t deadlineNs() const;
  std::int64_t stampNs();

  dds::Participant participant_;
  double timeout_s_;
  std::int64_t start_ns_;
  std::unique_ptr<Endpoints> endpoints_;
  std::unique_ptr<GoalEndpoints> goal_;
};

}  // namespace quad::launch
