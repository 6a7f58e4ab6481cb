// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/event_log.hpp"

#include <fmt/format.h>

namespace quad::display {

using Level = LogLine::Level;

std::optional<LogLine> EventLog::status(std::int64_t t_ns, const std::string& mode, const std::string& failsafe,
                                        bool failsafe_active)
{
  const auto now = std::make_pair(mode, failsafe);
  if (status_ == now) {
    return std::nullopt;
  }
  status_ = now;
  if (failsafe_active) {
    return LogLine{t_ns, Level::kWarning, "control", fmt::format("{}, failsafe: {}", mode, failsafe)};
  }
  return LogLine{t_ns, Level::kInfo, "control", failsafe.empty() ? mode : fmt::format("{} ({})", mode, failsafe)};
}

std::optional<LogLine> EventLog::path(std::int64_t t_ns, std::uint32_t goal_id, const std::string& status, bool ok,
                                      double cost_m, std::size_t waypoints)
{
  const auto now = std::make_pair(goal_id, status);
  if (path_ == now) {
    return std::nullopt;
  }
  path_ = now;
  if (!ok) {
    return LogLine{t_ns, Level::kWarning, "planning", fmt::format("goal {}: {}", goal_id, status)};
  }
  return LogLine{t_ns, Level::kInfo, "planning",
                 fmt::format("goal {}: path of {:.1f} m, {} waypoints", goal_id, cost_m, waypoints)};
}

LogLine EventLog::goalAnswer(std::int64_t t_ns, std::uint32_t goal_id, bool accepted, const std::string& reason) const
{
  return {t_ns, accepted ? Level::kInfo : Level::kWarning, "planning",
          fmt::format("goal {} {}: {}", goal_id, accepted ? "taken" : "refused", reason)};
}

LogLine EventLog::commandAnswer(std::int64_t t_ns, const std::string& command, bool accepted,
                                const std::string& reason) const
{
  return {t_ns, accepted ? Level::kInfo : Level::kWarning, "control",
          fmt::format("{} {}: {}", command, accepted ? "taken" : "refused", reason)};
}

LogLine EventLog::event(std::int64_t t_ns, const std::string& kind, const std::string& detail, EventClass cls,
                        bool from_fault_tool) const
{
  const Level level = cls == EventClass::kCollision ? Level::kError
                      : cls == EventClass::kFault || from_fault_tool ? Level::kWarning
                                                                       : Level::kInfo;
  return {t_ns, level, from_fault_tool ? "fault" : "plant", detail.empty() ? kind : fmt::format("{}: {}", kind, detail)};
}

}  // namespace quad::display
