// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The whole controller core: validated inputs, modes and failsafe, the path follower, the
/// SE(3) controller and the mixer, stepped once per vehicle state. No DDS: the node feeds it
/// and publishes what it returns.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "quad/common/geofence.hpp"
#include "quad/control/dead_reckoning.hpp"
#include "quad/control/geometric_controller.hpp"
#include "quad/control/land_detector.hpp"
#include "quad/control/mixer.hpp"
#include "quad/control/modes.hpp"
#include "quad/control/trajectory_follower.hpp"
#include "quad/vehicle/vehicle.hpp"

namespace quad::control {

/// What the planner's status makes of a path.
enum class PathKind {
  kOk,           ///< waypoints to fly
  kNone,         ///< no path to fly now (the map lags, the search is not done): hold
  kUnreachable,  ///< the planner says the goal cannot be reached: hold, then land
};

/// What the battery's monitor reads (quad/sim/battery).
struct BatteryReading {
  double voltage = 0.0;   ///< [V] at the terminals, under load
  double current = 0.0;   ///< [A]
  double charge = 1.0;    ///< fraction of the capacity left
  double capacity = 0.0;  ///< [Ah]
  int cells = 1;          ///< in series, as built
};

/// When the battery ends the flight (PX4's low/critical thresholds and its flight-time-left
/// return, in one rule each).
struct BatteryPolicy {
  double reserve = 0.15;               ///< fraction of the capacity to be left on landing
  double critical = 0.07;              ///< at or below this fraction left: land where it is
  double critical_cell_voltage = 3.3;  ///< [V] a cell's share of the pack's voltage under load, below which ...
  double critical_after = 1.0;         ///< [s] ... for this long (not one surge of current): land where it is
  double return_margin = 1.2;          ///< the way back is taken to last this many times its estimate ...
  double return_overhead = 5.0;        ///< [s] ... and this much more: braking, turning, touching down
  double current_window = 5.0;         ///< [s] the current drawn is averaged over about this long
};

struct FlightControllerConfig {
  GeometricGains gains;
  FollowerLimits follower;
  ModeConfig modes;
  double takeoff_altitude = 2.0;  ///< [m] above the take-off point
  /// [m] a take-off at the configured altitude climbs no closer than this to the geofence's
  /// ceiling: in a room fenced below it, it stops lower (an altitude asked for is not lowered)
  double takeoff_ceiling_margin = 0.5;
  double land_speed = 0.5;        ///< [m/s] descent in LAND
  double state_timeout = 0.1;     ///< [s] a state older than this is stale
  double path_timeout = 3.0;      ///< [s] a path not (re)published for this long is stale
  double goal_tolerance = 0.3;    ///< [m] default when the goal does not give one
  double failsafe_thrust = 0.85;  ///< fraction of the weight for a blind failsafe descent
  /// [s] how long after the last state the IMU may carry it on (0: never; then a stale state
  /// means a blind descent at once)
  double dead_reckoning_horizon = 5.0;
  /// [m] the camera gimbal looks at the path this far ahead of the vehicle
  double camera_look_ahead = 3.0;
  /// The keep-in volume: leaving it holds, then returns (ModeConfig::geofence_return_after).
  common::Geofence geofence;
  BatteryPolicy battery;
  /// Judges ground contact when the states do not tell it (an estimate).
  LandDetectorConfig land_detector;
  /// [s] the operator's station, once heard, silent this long: the link is lost and
  /// ModeConfig::link_loss acts (PX4's COM_DL_LOSS_T); 0: never.
  double link_loss_after = 10.0;
};

/// Where the camera gimbal should look: world yaw and elevation [rad].
struct CameraAim {
  double yaw_W = 0.0;
  double pitch = 0.0;
};

/// The controller's answer to an operator command, in the tick that applied it.
struct CommandAnswer {
  Command command = Command::kNone;
  /// Taken: its transition made, or nothing to change (hold while hovering). Refused: it does
  /// not apply in this mode, a value is out of range, or a failsafe overrode it this tick.
  bool accepted = false;
  std::string reason;  ///< refused: why; taken: the transition's why, or what already holds
};

struct FlightOutput {
  std::array<double, vehicle::kRotorCount> rotor_speed{};  ///< [rad/s]
  bool armed = false;
  Mode mode = Mode::kDisarmed;
  Reason reason = Reason::kNone;
  std::optional<Transition> transition;  ///< taken this tick
  std::string refused;                   ///< a command refused this tick, and why
  std::optional<CommandAnswer> answer;   ///< to the command applied this tick
  Reference reference;
  ControlOutput control;
  MixerOutput mixer;
  Vector3 position_error_W = Vector3::Zero();  ///< reference − actual
  Vector3 velocity_error_W = Vector3::Zero();
  double progress = 0.0;  ///< [m] arc length along the trajectory being flown
  /// Trajectories taken so far (TrajectoryFollower::taken()): a new value, a new trajectory
  std::uint32_t trajectories = 0;
  /// Flown on the IMU's dead reckoning from the last state (the state is stale)
  bool dead_reckoning = false;
  /// Where the depth camera looks: up on take-off, along the path ahead (the end of what the
  /// planner found known free comes into view before the vehicle stops at it), down when
  /// landing.
  CameraAim camera;
};

/// What a state's source says besides the state itself.
struct StateNotes {
  /// The plant's ground contact, when the source knows it (the truth); without, the land
  /// detector judges it.
  std::optional<bool> landed;
  /// An estimate's 1σ within the estimator's bounds (false: the uncertain-estimate failsafe).
  bool covariance_ok = true;
  /// The estimator's IMU biases, taken off the samples the dead reckoning integrates.
  Vector3 accel_bias_B = Vector3::Zero();  ///< [m/s²]
  Vector3 gyro_bias_B = Vector3::Zero();   ///< [rad/s]
};

class FlightController {
public:
  FlightController(const vehicle::VehicleParams& vehicle, FlightControllerConfig config);

  /// A vehicle state at sim time t [s], with what its source says of it. Rejected (false,
  /// counted) when non-finite (a bias too), the quaternion is not unit within 1e-3, or t goes back.
  bool onState(const VehicleState& state, double t, const StateNotes& notes = {});
  /// Whether the vehicle is taken to rest on the ground.
  bool landed() const { return landed_; }
  /// A planned path of the planner's status `kind` (waypoints are meaningful only when OK).
  /// The follower flies the path only up to `known_free_m` [m of arc length from its first
  /// waypoint]: there it leaves space the map knows free, and the vehicle must be able to stop
  /// before it. Rejected (false, counted) when a waypoint or `t` is non-finite, an OK path has
  /// none, or the known-free length is negative or NaN.
  bool onPath(const std::vector<Vector3>& waypoints, std::uint32_t version, PathKind kind, double t,
              double known_free_m = std::numeric_limits<double>::infinity());
  /// An IMU sample at sim time t [s], carrying the last state on while the state is stale
  /// (less the last state's biases). Rejected (false, counted) when non-finite.
  bool onImu(const InertialSample& sample, double t);
  /// A battery reading at sim time t [s]; rejected (false, counted) when a value is
  /// non-finite or out of its range (negative voltage or current, charge outside 0 … 1, no
  /// capacity, no cells).
  bool onBattery(const BatteryReading& reading, double t);
  /// A downward rangefinder's reading at sim time t [s]: how far below the body's origin the
  /// surface beneath lies [m] (+inf: nothing within `max_range`). The first state is judged
  /// standing or flying by it (LandDetector). Rejected (false, counted) when the range is
  /// negative or NaN, `max_range` not positive and finite, or t not finite.
  bool onRange(double range, double max_range, double t);
  /// An upward rangefinder's reading, as onRange's: how far above the body's origin the ceiling
  /// over it lies. A take-off at the configured altitude stops `takeoff_ceiling_margin` under
  /// the last one measured.
  bool onRangeUp(double range, double max_range, double t);
  /// [s] how long the charge left above the reserve lasts at the average current; infinite
  /// before any reading.
  double batteryTimeLeft() const;
  /// [s] the way back to the take-off point and the descent there, at the follower's top speed
  /// and the landing speed, times the policy's margin plus its overhead (0 on the ground).
  double returnTime() const;
  /// A heartbeat of the operator's station stamped at sim time t [s]; rejected (false,
  /// counted) when t is not finite.
  bool onOperatorHeartbeat(double t);
  /// The middleware's word (a DDS deadline event, on the wall clock) that no state came
  /// within its topic's deadline: the state counts as stale from the next update until a new
  /// one is taken, whatever the sim-time timeout says yet.
  void onStateLate() { state_late_ = true; }
  /// The same for the path: stale until the next one.
  void onPathLate() { path_late_ = true; }
  /// The goal the mission flies to, and whether to land once it is reached (else hover
  /// there); rejected (false, counted) when non-finite.
  bool onGoal(const Vector3& p, double tolerance, bool land = false);
  /// An operator command, applied (or refused) at the next update, which answers it. A
  /// take-off climbs `takeoff_altitude` [m] above the take-off point, or the configured
  /// altitude when it is 0, lowered to stay `takeoff_ceiling_margin` under the geofence's
  /// ceiling and the one measured above (onRangeUp); a negative or non-finite one, one whose
  /// top lies outside the geofence, or one under a ceiling too low to leave the ground
  /// (land_detector.ground_clearance), is refused.
  void onCommand(Command command, double takeoff_altitude = 0.0)
  {
    pending_ = command;
    pending_altitude_ = takeoff_altitude;
  }

  /// One control tick at sim time t [s].
  FlightOutput update(double t);

  std::uint64_t rejectedInputs() const { return rejected_; }
  /// An input the node refused before it reached the controller (published in the status).
  void countRejected() { ++rejected_; }
  Mode mode() const { return modes_.mode(); }
  Reason reason() const { return modes_.reason(); }
  std::optional<std::uint32_t> pathVersion() const { return path_version_; }
  /// What is flown: the trajectory, the path version it follows, the paths it refused.
  const TrajectoryFollower& follower() const { return follower_; }
  double lastStateTime() const { return state_t_; }

private:
  void enter(Mode from, Mode mode, double t, const std::optional<VehicleState>& state);
  /// How far a take-off asked to climb `altitude` (0: the configured one) climbs from `from`,
  /// or why it is refused (then `refused` says so and `up` is 0).
  struct TakeoffClimb {
    double up = 0.0;  ///< [m]
    std::string refused;
  };
  TakeoffClimb takeoffClimb(double altitude, const Vector3& from) const;
  /// The follower's path: the planner's, up to its known-free length.
  std::vector<Vector3> flyablePath() const;
  void aimCamera(Mode mode, const Vector3& p_W);

  vehicle::VehicleParams vehicle_;
  FlightControllerConfig config_;
  ModeMachine modes_;
  TrajectoryFollower follower_;
  GeometricController controller_;
  Mixer mixer_;
  DeadReckoning reckoning_;

  std::optional<VehicleState> state_;
  bool landed_ = true;
  LandDetector land_detector_;
  double overhead_ = std::numeric_limits<double>::infinity();  // [m] the ceiling over the body, measured
  bool judge_landing_ = false;  ///< the states do not say; the land detector judges
  double thrust_ratio_ = 0.0;   ///< the thrust last commanded, a fraction of the weight
  double state_t_ = -1.0;
  bool state_late_ = false;  // a deadline event since the last state
  StateNotes notes_;  // of the last state
  std::optional<InertialSample> imu_;  // the last IMU sample, for the land detector without a state
  double imu_t_ = 0.0;
  bool path_late_ = false;   // a deadline event since the last path
  std::vector<Vector3> path_;
  std::optional<std::uint32_t> path_version_;
  double path_known_free_ = 0.0;  // [m] of path_ flown
  PathKind path_kind_ = PathKind::kNone;  // of the last path heard
  CameraAim camera_;
  std::vector<Vector3> flown_;        // the flown path since take-off, a point every half metre
  double flown_length_ = 0.0;         // [m] along flown_
  std::vector<Vector3> return_path_;  // RETURN flies it: back along flown_
  double path_t_ = -1e300;
  bool path_changed_ = false;  // a path to fly that the follower has not taken yet
  double path_retry_t_ = -1e300;  // [s] when to try it (or the way back) again after the follower refused it
  double path_retry_period_ = 0.1;  // [s] until the next try
  bool return_pending_ = false;   // the way back, not taken yet
  std::optional<std::uint32_t> braking_for_;  // the path version refused that the follower brakes for
  std::optional<Vector3> goal_;
  double goal_tolerance_ = 0.3;
  bool land_at_goal_ = false;
  Command pending_ = Command::kNone;
  double pending_altitude_ = 0.0;  // [m] of a pending take-off; 0: the configured altitude
  double takeoff_altitude_ = 0.0;  // [m] of the take-off flown, above its point
  double last_update_t_ = -1.0;
  Vector3 takeoff_target_ = Vector3::Zero();
  Vector3 land_xy_ = Vector3::Zero();
  double land_z0_ = 0.0;
  double land_t0_ = 0.0;
  std::uint64_t rejected_ = 0;
  std::optional<double> operator_t_;     // [s] the operator's newest heartbeat
  std::optional<BatteryReading> battery_;
  double battery_t_ = 0.0;
  double average_current_ = 0.0;         // [A]
  double cells_low_since_ = -1.0;        // [s] since when the cells' voltage is below critical; -1: not
};

}  // namespace quad::control
