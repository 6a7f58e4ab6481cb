// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/modes.hpp"

namespace quad::control {

std::string_view toString(Mode m)
{
  switch (m) {
    case Mode::kDisarmed:
      return "DISARMED";
    case Mode::kIdle:
      return "IDLE";
    case Mode::kTakeoff:
      return "TAKEOFF";
    case Mode::kMission:
      return "MISSION";
    case Mode::kHover:
      return "HOVER";
    case Mode::kLand:
      return "LAND";
    case Mode::kFailsafeLand:
      return "FAILSAFE_LAND";
    case Mode::kReturn:
      return "RETURN";
  }
  return "?";
}

std::string_view toString(Reason r)
{
  switch (r) {
    case Reason::kNone:
      return "none";
    case Reason::kStateStale:
      return "state stale";
    case Reason::kPathStale:
      return "path stale";
    case Reason::kInputInvalid:
      return "input invalid";
    case Reason::kSaturation:
      return "saturation";
    case Reason::kCommanded:
      return "commanded";
    case Reason::kNoPath:
      return "no path";
    case Reason::kGeofence:
      return "geofence";
    case Reason::kBatteryLow:
      return "battery low";
    case Reason::kBatteryCritical:
      return "battery critical";
    case Reason::kLinkLost:
      return "link lost";
    case Reason::kEstimateUncertain:
      return "estimate uncertain";
  }
  return "?";
}

std::string_view toString(Command c)
{
  switch (c) {
    case Command::kNone:
      return "none";
    case Command::kArm:
      return "arm";
    case Command::kDisarm:
      return "disarm";
    case Command::kTakeoff:
      return "takeoff";
    case Command::kStartMission:
      return "start mission";
    case Command::kHold:
      return "hold";
    case Command::kLand:
      return "land";
    case Command::kReturn:
      return "return";
  }
  return "?";
}

bool airborne(Mode m)
{
  return m == Mode::kTakeoff || m == Mode::kMission || m == Mode::kHover || m == Mode::kLand ||
         m == Mode::kFailsafeLand || m == Mode::kReturn;
}

ModeMachine::ModeMachine(ModeConfig config) : config_(config) {}

std::optional<Transition> ModeMachine::go(Mode to, Reason reason, std::string why, double t)
{
  Transition tr{mode_, to, reason, std::move(why)};
  mode_ = to;
  reason_ = reason;
  entered_ = t;
  path_stale_since_ = -1.0;
  no_path_since_ = reason == Reason::kNoPath ? t : -1.0;  // the hold counts from the planner's word
  return tr;
}

std::optional<Transition> ModeMachine::update(const ModeInputs& in)
{
  refused_.clear();
  const auto commanded = [&](Command c) { return in.command == c; };
  const auto refuse = [&](const char* why) {
    refused_ = std::string(toString(in.command)) + " refused in " + std::string(toString(mode_)) + ": " + why;
  };

  // Safety first: losing the state while flying lands, whatever was asked; while the IMU
  // carries the last state on, after a hold for it to come back (a restarted estimator).
  if (in.state_fresh) {
    stale_since_ = -1.0;
  } else if (airborne(mode_) && mode_ != Mode::kFailsafeLand) {
    if (stale_since_ < 0.0) {
      stale_since_ = in.t;
    }
    const bool holding = mode_ == Mode::kHover && reason_ == Reason::kStateStale;
    if (!in.dead_reckoning || mode_ == Mode::kLand || commanded(Command::kLand) ||
        in.t - stale_since_ >= config_.state_stale_land_after) {
      return go(Mode::kFailsafeLand, Reason::kStateStale,
                holding ? "vehicle state stale too long: landing" : "vehicle state stale", in.t);
    }
    if (in.command != Command::kNone) {
      refuse("holding without a vehicle state");
    }
    return holding ? std::nullopt
                   : go(Mode::kHover, Reason::kStateStale, "vehicle state stale: holding on dead reckoning", in.t);
  }
  if (!in.estimate_uncertain || !in.state_fresh) {
    uncertain_since_ = -1.0;
  } else if (uncertain_since_ < 0.0) {
    uncertain_since_ = in.t;
  }
  if (commanded(Command::kDisarm)) {
    if (mode_ == Mode::kDisarmed) {
      return std::nullopt;
    }
    if (!in.landed) {
      refuse("the vehicle is in the air");
      return std::nullopt;
    }
    return go(Mode::kDisarmed, Reason::kCommanded, "commanded: disarm", in.t);
  }

  switch (mode_) {
    case Mode::kDisarmed:
      // Only a controller started while the vehicle flies is disarmed in the air (disarming in
      // flight is refused, and disarming on the ground needs it landed): take over where the
      // vehicle is, whatever was asked, rather than let it fall.
      if (in.state_fresh && !in.landed) {
        return go(Mode::kHover, Reason::kNone, "took over in the air: holding position", in.t);
      }
      if (commanded(Command::kArm)) {
        if (!in.landing_judged) {
          refuse("what the vehicle stands on is not judged yet (waiting for the rangefinder)");
          return std::nullopt;
        }
        if (!in.landed || !in.state_fresh) {
          refuse(!in.landed ? "not on the ground" : "no fresh vehicle state");
          return std::nullopt;
        }
        return go(Mode::kIdle, Reason::kCommanded, "commanded: arm", in.t);
      }
      if (in.command != Command::kNone) {
        refuse("arm first");
      }
      return std::nullopt;
    case Mode::kIdle:
      if (commanded(Command::kTakeoff)) {
        if (!in.state_fresh) {
          refuse("no fresh vehicle state");
          return std::nullopt;
        }
        if (in.estimate_uncertain) {
          refuse("the state estimate is uncertain");
          return std::nullopt;
        }
        if (in.battery_low || in.battery_critical) {
          refuse(in.battery_critical ? "battery critical" : "battery down to its reserve");
          return std::nullopt;
        }
        return go(Mode::kTakeoff, Reason::kCommanded, "commanded: takeoff", in.t);
      }
      if (in.t - entered_ >= config_.idle_disarm_after) {
        return go(Mode::kDisarmed, Reason::kNone, "idle on the ground: disarmed", in.t);
      }
      if (in.command != Command::kNone && !commanded(Command::kArm)) {
        refuse("take off first");
      }
      return std::nullopt;
    case Mode::kFailsafeLand:
      if (in.landed) {
        return go(Mode::kIdle, Reason::kStateStale, "landed after failsafe", in.t);
      }
      if (in.command != Command::kNone) {
        refuse("failsafe landing");
      }
      return std::nullopt;
    default:
      break;
  }

  // Airborne modes with a fresh state. Refusals here do not end the tick: the failsafes below
  // still act on it.
  if (commanded(Command::kArm) || commanded(Command::kTakeoff)) {
    refuse("already in the air");
  }
  if (commanded(Command::kLand) && mode_ != Mode::kLand) {
    return go(Mode::kLand, Reason::kCommanded, "commanded: land", in.t);
  }
  // A battery about to fail lands where the vehicle is: no way back is short enough.
  if (in.battery_critical && mode_ != Mode::kLand) {
    return go(Mode::kLand, Reason::kBatteryCritical, "battery critical: landing where it is", in.t);
  }
  const bool returning_for_battery = mode_ == Mode::kReturn && reason_ == Reason::kBatteryLow;
  if (returning_for_battery && (commanded(Command::kStartMission) || commanded(Command::kHold))) {
    refuse("returning on a low battery");
    return std::nullopt;
  }
  const bool flying_out = mode_ == Mode::kTakeoff || mode_ == Mode::kMission || mode_ == Mode::kHover;
  if (commanded(Command::kReturn)) {
    if (mode_ == Mode::kReturn) {
      return std::nullopt;
    }
    if (!flying_out) {
      refuse("landing already");
      return std::nullopt;
    }
    return go(Mode::kReturn, Reason::kCommanded, "commanded: return to launch", in.t);
  }
  // The operator's station fell silent: by policy, back the way the vehicle came, or down.
  if (in.link_lost && flying_out && config_.link_loss != LinkLossAction::kNone) {
    if (config_.link_loss == LinkLossAction::kLand) {
      return go(Mode::kLand, Reason::kLinkLost, "operator link lost: landing where it is", in.t);
    }
    return go(Mode::kReturn, Reason::kLinkLost, "operator link lost: returning to land at the take-off point", in.t);
  }
  // Only as much charge left as the way back needs: go back now, the way the vehicle came.
  if (in.battery_low && flying_out) {
    return go(Mode::kReturn, Reason::kBatteryLow, "battery low: returning to land at the take-off point", in.t);
  }
  if (commanded(Command::kHold) && mode_ != Mode::kHover) {
    return go(Mode::kHover, Reason::kCommanded, "commanded: hold", in.t);
  }
  // Pushed out of the keep-in volume: brake and hold where it is, then return. RETURN and
  // the landings carry on wherever they are.
  const bool holding_for_fence = mode_ == Mode::kHover && reason_ == Reason::kGeofence;
  if (in.outside_geofence && !holding_for_fence &&
      (mode_ == Mode::kTakeoff || mode_ == Mode::kMission || mode_ == Mode::kHover)) {
    return go(Mode::kHover, Reason::kGeofence, "outside the geofence: holding", in.t);
  }
  if (holding_for_fence) {
    if (commanded(Command::kStartMission)) {
      refuse("holding after leaving the geofence");
      return std::nullopt;
    }
    if (in.t - entered_ >= config_.geofence_return_after) {
      return go(Mode::kReturn, Reason::kGeofence, "left the geofence: returning to land at the take-off point", in.t);
    }
    return std::nullopt;
  }
  // The estimate's 1-sigma past its bounds (a position source lost for long, a filter gone
  // astray): hold where the estimate says the vehicle is, for a fix to bring it back (the
  // mission then resumes), and land there if none does. A return carries on, as far as the
  // same time allows.
  if (in.estimate_uncertain) {
    const bool holding_for_estimate = mode_ == Mode::kHover && reason_ == Reason::kEstimateUncertain;
    if (holding_for_estimate && commanded(Command::kStartMission)) {
      refuse("holding on an uncertain state estimate");
      return std::nullopt;
    }
    if ((holding_for_estimate || mode_ == Mode::kReturn) && in.t - uncertain_since_ >= config_.uncertain_land_after) {
      return go(Mode::kLand, Reason::kEstimateUncertain, "state estimate uncertain too long: landing", in.t);
    }
    if (holding_for_estimate) {
      return std::nullopt;
    }
    if (flying_out) {
      return go(Mode::kHover, Reason::kEstimateUncertain, "state estimate uncertain: holding", in.t);
    }
  }
  switch (mode_) {
    case Mode::kTakeoff:
      if (commanded(Command::kStartMission)) {
        refuse("taking off: the mission starts once the take-off altitude is reached");
      }
      if (in.takeoff_altitude_reached) {
        return go(Mode::kHover, Reason::kNone, "takeoff altitude reached", in.t);
      }
      break;
    case Mode::kHover:
      if (commanded(Command::kStartMission) ||
          (config_.auto_mission && in.path_fresh && !in.goal_reached && reason_ != Reason::kCommanded)) {
        if (!in.path_fresh) {
          refuse("no fresh path");
          return std::nullopt;
        }
        return go(Mode::kMission, commanded(Command::kStartMission) ? Reason::kCommanded : Reason::kNone,
                  commanded(Command::kStartMission) ? "commanded: start mission" : "path available", in.t);
      }
      // The planner says the goal cannot be reached: hold, for a map that was wrong to
      // right itself, then go back the way the vehicle came (what lies below it now may be
      // an obstacle's roof) and land where it took off.
      if (in.no_path) {
        if (no_path_since_ < 0.0) {
          no_path_since_ = in.t;
        }
        if (in.t - no_path_since_ >= config_.no_path_land_after) {
          return go(Mode::kReturn, Reason::kNoPath, "no path to the goal: returning to land at the take-off point",
                    in.t);
        }
        break;
      }
      no_path_since_ = -1.0;
      if (reason_ == Reason::kPathStale) {
        if (in.path_fresh) {
          path_stale_since_ = -1.0;
        } else {
          if (path_stale_since_ < 0.0) {
            path_stale_since_ = entered_;
          }
          if (in.t - path_stale_since_ >= config_.path_stale_land_after) {
            return go(Mode::kLand, Reason::kPathStale, "path stale too long: landing", in.t);
          }
        }
      }
      break;
    case Mode::kMission:
      if (in.no_path) {
        return go(Mode::kHover, Reason::kNoPath, "no path to the goal", in.t);
      }
      if (!in.path_fresh) {
        return go(Mode::kHover, Reason::kPathStale, "path stale", in.t);
      }
      if (in.goal_reached) {
        return in.land_at_goal ? go(Mode::kLand, Reason::kNone, "goal reached: landing there", in.t)
                               : go(Mode::kHover, Reason::kNone, "goal reached", in.t);
      }
      break;
    case Mode::kLand:
      if (commanded(Command::kStartMission)) {
        refuse("landing: hold first");
      }
      if (in.landed) {
        const bool told = reason_ == Reason::kNoPath || reason_ == Reason::kGeofence || reason_ == Reason::kBatteryLow ||
                          reason_ == Reason::kBatteryCritical || reason_ == Reason::kLinkLost ||
                          reason_ == Reason::kEstimateUncertain;  // why the flight ended
        return go(Mode::kIdle, told ? reason_ : Reason::kNone, "landed", in.t);
      }
      break;
    case Mode::kReturn:
      if (commanded(Command::kStartMission)) {
        refuse("returning: hold first");
      }
      if (in.returned) {
        return go(Mode::kLand, reason_, "back above the take-off point: landing", in.t);
      }
      break;
    default:
      break;
  }
  return std::nullopt;
}

}  // namespace quad::control
