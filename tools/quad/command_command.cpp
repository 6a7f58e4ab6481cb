// SPDX-License-Identifier: BSD-3-Clause
#include "command_command.hpp"

#include <cstdio>
#include <stdexcept>

#include "quad/launch/operator_station.hpp"

namespace quad::tools {

namespace {

using launch::OperatorAnswer;
using launch::OperatorCommand;

int report(const std::string& what, const OperatorAnswer& answer)
{
  switch (answer.outcome) {
    case OperatorAnswer::Outcome::kTaken:
      std::printf("%s: taken: %s%s\n", what.c_str(), answer.text.c_str(),
                  answer.mode.empty() ? "" : (" (now " + answer.mode + ")").c_str());
      return 0;
    case OperatorAnswer::Outcome::kRefused:
      std::fprintf(stderr, "%s: refused: %s%s\n", what.c_str(), answer.text.c_str(),
                   answer.mode.empty() ? "" : (" (still " + answer.mode + ")").c_str());
      return 1;
    case OperatorAnswer::Outcome::kNoAnswer:
      std::fprintf(stderr, "%s: %s\n", what.c_str(), answer.text.c_str());
      return 3;
  }
  return 3;
}

OperatorCommand simpleCommand(const std::string& verb)
{
  if (verb == "arm") {
    return OperatorCommand::kArm;
  }
  if (verb == "disarm") {
    return OperatorCommand::kDisarm;
  }
  if (verb == "hold") {
    return OperatorCommand::kHold;
  }
  if (verb == "land") {
    return OperatorCommand::kLand;
  }
  if (verb == "return") {
    return OperatorCommand::kReturn;
  }
  throw std::invalid_argument("unknown command '" + verb + "'");
}

}  // namespace

int command(const CommandOptions& options)
{
  const bool goal_verb = options.verb == "goal" || options.verb == "goto";
  if (goal_verb && !(options.position.size() == 3 || (options.verb == "goto" && options.position.empty()))) {
    std::fprintf(stderr, "quad command %s: a position is x y z, got %zu numbers\n", options.verb.c_str(),
                 options.position.size());
    return 2;
  }
  try {
    launch::OperatorStation station(topic::participantOptions("quad_command", options.connection), options.timeout_s);
    if (options.verb == "takeoff") {
      // As PX4's commander: a take-off arms a disarmed vehicle first.
      if (station.mode() == "DISARMED") {
        if (const int rc = report("arm", station.command(OperatorCommand::kArm)); rc != 0) {
          return rc;
        }
      }
      return report("takeoff", station.command(OperatorCommand::kTakeoff, options.altitude));
    }
    if (goal_verb) {
      if (!options.position.empty()) {
        const Eigen::Vector3d p(options.position[0], options.position[1], options.position[2]);
        if (const int rc = report("goal", station.setGoal(p, options.tolerance)); rc != 0 || options.verb == "goal") {
          return rc;
        }
      }
      return report("goto", station.command(OperatorCommand::kStartMission));
    }
    return report(options.verb, station.command(simpleCommand(options.verb)));
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "quad command %s: %s\n", options.verb.c_str(), e.what());
    return 2;
  }
}

}  // namespace quad::tools
