// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The controller's modes and failsafe: a pure state machine, stepped with what the node
/// observed this tick. Every transition has a reason, which the node publishes.
///
///   DISARMED --arm--> IDLE --takeoff--> TAKEOFF --altitude--> HOVER --mission--> MISSION
///   DISARMED --in the air (a controller started in flight)--> HOVER, where the vehicle is
///   MISSION --goal reached--> HOVER;  any airborne --land--> LAND --landed--> IDLE
///   MISSION --path stale--> HOVER --path still stale for path_stale_land_after--> LAND
///   MISSION --no path--> HOVER --still no path for no_path_land_after--> RETURN --back--> LAND
///     (the planner says the goal cannot be reached: sealed off, in an obstacle, out of bounds;
///     RETURN retraces the flown path to the take-off point, the one way known to be clear,
///     and lands there)
///   TAKEOFF, MISSION, HOVER --outside the geofence--> HOVER --geofence_return_after--> RETURN
///     (the vehicle was pushed out of the keep-in volume: it brakes and holds, then goes back
///     the way it came, which lay inside, and lands at the take-off point)
///   TAKEOFF, MISSION, HOVER --battery low--> RETURN --back--> LAND
///     (the charge left, less a reserve, lasts no longer than the way back and the descent)
///   any airborne but LAND and FAILSAFE_LAND --battery critical--> LAND, where it is
///   TAKEOFF, MISSION, HOVER --return commanded--> RETURN --back--> LAND
///   TAKEOFF, MISSION, HOVER --operator's link lost--> RETURN (or LAND, by ModeConfig::link_loss)
///   TAKEOFF, MISSION, HOVER --estimate uncertain--> HOVER --still for uncertain_land_after--> LAND
///     (the estimator's 1-sigma past its bounds: a position source lost for long; it holds
///     where the estimate says it is, for a fix to come back, and resumes if one does)
///   RETURN --estimate uncertain for uncertain_land_after--> LAND
///   TAKEOFF, MISSION, HOVER, RETURN --state stale, dead reckoning--> HOVER
///     --stale for state_stale_land_after (or the reckoning ends)--> FAILSAFE_LAND
///     (the IMU carries the last state on: it holds, for the state to come back, as a
///     restarted estimator's does, and the mission resumes)
///   any airborne --state stale, no dead reckoning--> FAILSAFE_LAND --landed--> IDLE
///     --idle timeout--> DISARMED

#include <optional>
#include <string>
#include <string_view>

namespace quad::control {

enum class Mode { kDisarmed, kIdle, kTakeoff, kMission, kHover, kLand, kFailsafeLand, kReturn };
enum class Reason {
  kNone,
  kStateStale,
  kPathStale,
  kInputInvalid,
  kSaturation,
  kCommanded,
  kNoPath,
  kGeofence,
  kBatteryLow,
  kBatteryCritical,
  kLinkLost,
  kEstimateUncertain
};
enum class Command { kNone, kArm, kDisarm, kTakeoff, kStartMission, kHold, kLand, kReturn };
/// What the controller does when the operator's station falls silent (PX4's NAV_DLL_ACT).
enum class LinkLossAction { kReturn, kLand, kNone };

std::string_view toString(Mode m);
std::string_view toString(Reason r);
std::string_view toString(Command c);

bool airborne(Mode m);

struct ModeInputs {
  double t = 0.0;                 ///< [s] now
  Command command = Command::kNone;
  bool state_fresh = true;        ///< a valid state within its timeout
  /// The state is stale but the IMU carries the last one on (within its horizon)
  bool dead_reckoning = false;
  bool path_fresh = false;        ///< a valid path (status OK) within its timeout
  bool no_path = false;           ///< the planner's latest word: the goal cannot be reached
  bool landed = true;
  /// The land detector has judged the first state (landed is its word); before, arming waits.
  bool landing_judged = true;
  bool takeoff_altitude_reached = false;
  bool goal_reached = false;
  bool land_at_goal = false;      ///< the goal asks to land once it is reached
  bool returned = false;          ///< in RETURN: back above the take-off point
  bool outside_geofence = false;  ///< the vehicle is outside the keep-in volume
  /// The charge left, less the reserve, lasts no longer than the way back to the take-off
  /// point and the descent there (on the ground: the charge is down to the reserve).
  bool battery_low = false;
  bool battery_critical = false;  ///< the pack is nearly empty or a cell has failed: land now
  bool link_lost = false;         ///< the operator's station, once heard, has been silent too long
  /// The state is an estimate whose 1-sigma is past the estimator's bounds
  bool estimate_uncertain = false;
};

struct ModeConfig {
  double path_stale_land_after = 5.0;  ///< [s] in HOVER without a path before landing
  double state_stale_land_after = 2.5; ///< [s] holding on dead reckoning without a state before landing
  double no_path_land_after = 5.0;     ///< [s] in HOVER while the planner finds no path, before returning to land
  double idle_disarm_after = 10.0;     ///< [s] on the ground, armed, before disarming
  double geofence_return_after = 1.0;  ///< [s] holding after leaving the geofence, before returning
  double uncertain_land_after = 5.0;   ///< [s] on an uncertain estimate, holding or returning, before landing
  /// HOVER with a fresh path starts the mission by itself, unless the operator commanded the hold
  bool auto_mission = false;
  LinkLossAction link_loss = LinkLossAction::kReturn;  ///< when the operator's link is lost
};

struct Transition {
  Mode from;
  Mode to;
  Reason reason;
  std::string why;  ///< "path stale", "commanded: land", ...
};

class ModeMachine {
public:
  explicit ModeMachine(ModeConfig config = {});

  Mode mode() const { return mode_; }
  Reason reason() const { return reason_; }

  /// One tick. Returns the transition taken, if any. A command that does not apply in the
  /// current mode (disarm while flying, mission without a path) is refused: no transition for
  /// it, and `refused` says why. A command that asks for what already holds (hold while
  /// hovering) changes nothing; one that a failsafe overrides in the same tick gives way to it
  /// (the transition is the failsafe's).
  std::optional<Transition> update(const ModeInputs& in);

  const std::string& refused() const { return refused_; }

private:
  std::optional<Transition> go(Mode to, Reason reason, std::string why, double t);

  ModeConfig config_;
  Mode mode_ = Mode::kDisarmed;
  Reason reason_ = Reason::kNone;
  double entered_ = 0.0;          // time the current mode began
  double path_stale_since_ = -1;  // time the path went stale in HOVER, -1 if fresh
  double no_path_since_ = -1;     // time the planner first said no path in HOVER, -1 if it did not
  double uncertain_since_ = -1;   // time the estimate became uncertain in the air, -1 if it is not
  double stale_since_ = -1;       // time the state went stale in the air, -1 if it is fresh
  std::string refused_;
};

}  // namespace quad::control
