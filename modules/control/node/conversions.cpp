// SPDX-License-Identifier: BSD-3-Clause
#include "conversions.hpp"

#include "quad/dds/geometry_messages.hpp"

namespace quad::control {

using dds::toMessage;

VehicleState fromSample(const runtime::StateSample& s) { return {s.p_W, s.v_W, s.q_WB, s.w_B}; }

std::vector<Vector3> waypointsOf(const msg::Path& m)
{
  std::vector<Vector3> out;
  out.reserve(m.waypoints_W().size());
  for (const auto& w : m.waypoints_W()) {
    out.push_back(dds::toVector(w));
  }
  return out;
}

Command fromMessage(msg::CommandKind kind)
{
  switch (kind) {
    case msg::COMMAND_ARM:
      return Command::kArm;
    case msg::COMMAND_DISARM:
      return Command::kDisarm;
    case msg::COMMAND_TAKEOFF:
      return Command::kTakeoff;
    case msg::COMMAND_START_MISSION:
      return Command::kStartMission;
    case msg::COMMAND_HOLD:
      return Command::kHold;
    case msg::COMMAND_LAND:
      return Command::kLand;
    case msg::COMMAND_RETURN:
      return Command::kReturn;
    case msg::COMMAND_SAVE_MAP:
      return Command::kNone;  // the mapper's
  }
  return Command::kNone;
}

msg::ControlMode toMessage(Mode mode)
{
  switch (mode) {
    case Mode::kDisarmed:
      return msg::CONTROL_DISARMED;
    case Mode::kIdle:
      return msg::CONTROL_IDLE;
    case Mode::kTakeoff:
      return msg::CONTROL_TAKEOFF;
    case Mode::kMission:
      return msg::CONTROL_MISSION;
    case Mode::kHover:
      return msg::CONTROL_HOVER;
    case Mode::kLand:
      return msg::CONTROL_LAND;
    case Mode::kFailsafeLand:
      return msg::CONTROL_FAILSAFE_LAND;
    case Mode::kReturn:
      return msg::CONTROL_RETURN;
  }
  return msg::CONTROL_DISARMED;
}

PathKind pathKind(msg::PlanStatus status)
{
  switch (status) {
    case msg::PLAN_OK:
      return PathKind::kOk;
    case msg::PLAN_GOAL_ENCLOSED:
    case msg::PLAN_START_ENCLOSED:
    case msg::PLAN_GOAL_BLOCKED:
    case msg::PLAN_OUT_OF_BOUNDS:
      return PathKind::kUnreachable;
    default:
      return PathKind::kNone;  // passing: the map lags, the search is not done, the mapper is lost
  }
}

msg::FailsafeReason toMessage(Reason reason)
{
  switch (reason) {
    case Reason::kNone:
      return msg::FAILSAFE_NONE;
    case Reason::kStateStale:
      return msg::FAILSAFE_STATE_STALE;
    case Reason::kPathStale:
      return msg::FAILSAFE_PATH_STALE;
    case Reason::kInputInvalid:
      return msg::FAILSAFE_INPUT_INVALID;
    case Reason::kSaturation:
      return msg::FAILSAFE_SATURATION;
    case Reason::kCommanded:
      return msg::FAILSAFE_COMMANDED;
    case Reason::kNoPath:
      return msg::FAILSAFE_NO_PATH;
    case Reason::kGeofence:
      return msg::FAILSAFE_GEOFENCE;
    case Reason::kBatteryLow:
      return msg::FAILSAFE_BATTERY_LOW;
    case Reason::kBatteryCritical:
      return msg::FAILSAFE_BATTERY_CRITICAL;
    case Reason::kLinkLost:
      return msg::FAILSAFE_LINK_LOST;
    case Reason::kEstimateUncertain:
      return msg::FAILSAFE_ESTIMATE_UNCERTAIN;
  }
  return msg::FAILSAFE_NONE;
}

msg::ControlReference toMessage(const Reference& r, double progress)
{
  msg::ControlReference m;
  m.p_W(toMessage(r.p_W));
  m.v_W(toMessage(r.v_W));
  m.a_W(toMessage(r.a_W));
  m.yaw(r.yaw);
  m.yaw_rate(r.yaw_rate);
  m.progress(progress);
  return m;
}

}  // namespace quad::control
