// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The flight's events as log lines for a viewer's log panel: the controller's mode and
/// failsafe at each change, the planner's answers and its status at each change, simulator
/// and fault events, the answers to operator commands. Each line names the module it is
/// about; its level says how much it matters (a failsafe or a refusal warns, a collision is
/// an error).

#include <cstdint>
#include <optional>
#include <string>

namespace quad::display {

struct LogLine {
  enum class Level { kDebug, kInfo, kWarning, kError };
  std::int64_t t_ns = 0;  ///< the stamp of what it reports
  Level level = Level::kInfo;
  std::string source;  ///< the module: "control", "planning", "plant", "fault"
  std::string text;
};

class EventLog {
public:
  /// The controller's status: a line when its mode or its reason for it changed (the first
  /// status is a change). `failsafe` names the reason (empty: none); `failsafe_active` says
  /// whether it is a failsafe's (it warns) rather than, say, the operator's command.
  std::optional<LogLine> status(std::int64_t t_ns, const std::string& mode, const std::string& failsafe,
                                bool failsafe_active);
  /// A path: a line when its status changed, or when it leads to a new goal.
  std::optional<LogLine> path(std::int64_t t_ns, std::uint32_t goal_id, const std::string& status, bool ok,
                              double cost_m, std::size_t waypoints);
  /// A goal's answer from the planner.
  LogLine goalAnswer(std::int64_t t_ns, std::uint32_t goal_id, bool accepted, const std::string& reason) const;
  /// An operator command's answer from the controller.
  LogLine commandAnswer(std::int64_t t_ns, const std::string& command, bool accepted, const std::string& reason) const;
  enum class EventClass { kCollision, kFault, kOther };
  /// A simulator event (a collision, a fault applied, ground contact) or, with
  /// `from_fault_tool`, a fault applied outside the plant.
  LogLine event(std::int64_t t_ns, const std::string& kind, const std::string& detail, EventClass cls,
                bool from_fault_tool) const;

private:
  std::optional<std::pair<std::string, std::string>> status_;  // mode, failsafe
  std::optional<std::pair<std::uint32_t, std::string>> path_;  // goal, status
};

}  // namespace quad::display
