// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/flight_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "quad/geometry/polyline.hpp"
#include "quad/geometry/so3.hpp"

namespace quad::control {

namespace {
constexpr double kBreadcrumbSpacing = 0.5;  // [m] between the flown path's points kept for a return
constexpr double kPathRetryPeriod = 0.1;    // [s] between the first tries of a path the follower refused ...
constexpr double kPathRetryLongest = 0.8;   // [s] ... growing up to this while it keeps refusing it

double yawOf(const Quaternion& q)
{
  const Vector3 x = geometry::toMatrix(q).col(0);
  return std::atan2(x.y(), x.x());
}

CommandAnswer answerTo(Command command, const std::optional<Transition>& transition, const std::string& refused,
                       Mode mode)
{
  const std::string name(toString(command));
  if (!refused.empty()) {
    return {command, false, refused};
  }
  if (transition && transition->reason != Reason::kCommanded) {
    return {command, false, name + " overridden in " + std::string(toString(transition->from)) + ": " + transition->why};
  }
  if (transition) {
    return {command, true, transition->why};
  }
  return {command, true, name + ": nothing to change in " + std::string(toString(mode))};
}
}  // namespace

FlightController::FlightController(const vehicle::VehicleParams& vehicle, FlightControllerConfig config)
    : vehicle_(vehicle),
      config_(config),
      modes_(config.modes),
      follower_(config.follower, generatorConfig(config.follower, vehicle, config.gains.max_tilt)),
      controller_(vehicle.mass, vehicle.inertia, config.gains),
      mixer_(vehicle),
      land_detector_(config.land_detector),
      goal_tolerance_(config.goal_tolerance)
{
}

bool FlightController::onState(const VehicleState& s, double t, const StateNotes& notes)
{
  const double n = s.q_WB.norm();
  const bool valid = s.p_W.allFinite() && s.v_W.allFinite() && s.w_B.allFinite() && std::isfinite(n) &&
                     std::abs(n - 1.0) < 1e-3 && std::isfinite(t) && t >= state_t_ &&
                     notes.accel_bias_B.allFinite() && notes.gyro_bias_B.allFinite();
  if (!valid) {
    ++rejected_;
    return false;
  }
  state_ = VehicleState{s.p_W, s.v_W, s.q_WB.normalized(), s.w_B};
  judge_landing_ = !notes.landed.has_value();
  if (notes.landed) {
    landed_ = *notes.landed;
  }
  state_t_ = t;
  state_late_ = false;
  notes_ = notes;
  reckoning_.anchor(*state_, t);
  return true;
}

bool FlightController::onImu(const InertialSample& sample, double t)
{
  const InertialSample corrected{sample.specific_force_B - notes_.accel_bias_B,
                                 sample.angular_rate_B - notes_.gyro_bias_B};
  if (!reckoning_.onImu(corrected, t)) {
    ++rejected_;
    return false;
  }
  if (!imu_ || t >= imu_t_) {
    imu_ = sample;
    imu_t_ = t;
  }
  return true;
}

bool FlightController::onPath(const std::vector<Vector3>& waypoints, std::uint32_t version, PathKind kind, double t,
                              double known_free_m)
{
  const bool ok = kind == PathKind::kOk;
  const bool finite = std::all_of(waypoints.begin(), waypoints.end(), [](const Vector3& w) { return w.allFinite(); });
  if (!finite || (ok && waypoints.empty()) || !std::isfinite(t) || !(known_free_m >= 0.0)) {
    ++rejected_;
    return false;
  }
  path_t_ = t;
  path_late_ = false;
  path_kind_ = kind;
  if (ok && (!path_version_ || version != *path_version_)) {
    path_ = waypoints;
    path_version_ = version;
    path_known_free_ = known_free_m;
    path_changed_ = true;
    path_retry_t_ = -1e300;  // a new path: tried at once
    path_retry_period_ = kPathRetryPeriod / 2.0;
  }
  return true;
}

std::vector<Vector3> FlightController::flyablePath() const { return geometry::truncated(path_, path_known_free_); }

void FlightController::aimCamera(Mode mode, const Vector3& p_W)
{
  Vector3 look = Vector3::Zero();
  switch (mode) {
    case Mode::kTakeoff:
      look = Vector3::UnitZ();  // the column it climbs into
      break;
    case Mode::kLand:
    case Mode::kFailsafeLand:
      look = -Vector3::UnitZ();  // the column it descends into
      break;
    case Mode::kMission:
    case Mode::kHover:
    case Mode::kReturn: {
      const std::vector<Vector3>& path = mode == Mode::kReturn ? return_path_ : path_;
      if (path.size() >= 2) {
        const double s = geometry::nearestArcLength(path, p_W) + config_.camera_look_ahead;
        look = geometry::pointAlong(path, s) - p_W;
      }
      break;
    }
    default:
      break;
  }
  if (look.norm() < 0.3) {
    return;  // nothing to look at, or too close to tell a direction: keep the aim
  }
  const double horizontal = look.head<2>().norm();
  if (horizontal > 0.05 * look.norm()) {
    camera_.yaw_W = std::atan2(look.y(), look.x());
  }
  camera_.pitch = std::atan2(look.z(), horizontal);
}

namespace {
bool validRange(double range, double max_range, double t)
{
  return std::isfinite(t) && !std::isnan(range) && range >= 0.0 && std::isfinite(max_range) && max_range > 0.0;
}
}  // namespace

bool FlightController::onRange(double range, double max_range, double t)
{
  if (!validRange(range, max_range, t)) {
    ++rejected_;
    return false;
  }
  land_detector_.onRange(range <= max_range ? std::optional<double>(range) : std::nullopt);
  return true;
}

bool FlightController::onRangeUp(double range, double max_range, double t)
{
  if (!validRange(range, max_range, t)) {
    ++rejected_;
    return false;
  }
  overhead_ = range <= max_range ? range : std::numeric_limits<double>::infinity();
  return true;
}

bool FlightController::onBattery(const BatteryReading& b, double t)
{
  const bool valid = std::isfinite(t) && std::isfinite(b.voltage) && b.voltage >= 0.0 && std::isfinite(b.current) &&
                     b.current >= 0.0 && b.charge >= 0.0 && b.charge <= 1.0 && std::isfinite(b.capacity) &&
                     b.capacity > 0.0 && b.cells >= 1 && (!battery_ || t >= battery_t_);
  if (!valid) {
    ++rejected_;
    return false;
  }
  const BatteryPolicy& policy = config_.battery;
  if (!battery_) {
    average_current_ = b.current;
  } else {
    const double weight = 1.0 - std::exp(-(t - battery_t_) / policy.current_window);
    average_current_ += weight * (b.current - average_current_);
  }
  if (b.voltage / b.cells >= policy.critical_cell_voltage) {
    cells_low_since_ = -1.0;
  } else if (cells_low_since_ < 0.0) {
    cells_low_since_ = t;
  }
  battery_ = b;
  battery_t_ = t;
  return true;
}

bool FlightController::onOperatorHeartbeat(double t)
{
  if (!std::isfinite(t)) {
    ++rejected_;
    return false;
  }
  operator_t_ = std::max(t, operator_t_.value_or(t));
  return true;
}

double FlightController::batteryTimeLeft() const
{
  if (!battery_) {
    return std::numeric_limits<double>::infinity();
  }
  const double usable = std::max(0.0, battery_->charge - config_.battery.reserve) * battery_->capacity;  // [Ah]
  return average_current_ > 0.0 ? usable * 3600.0 / average_current_ : std::numeric_limits<double>::infinity();
}

double FlightController::returnTime() const
{
  if (!state_ || landed_ || !airborne(modes_.mode())) {
    return 0.0;
  }
  // Back along the flown path (RETURN's way) to above the take-off point, then down.
  const double way = flown_.empty() ? 0.0 : (state_->p_W - flown_.back()).norm() + flown_length_;
  const double ground = takeoff_target_.z() - takeoff_altitude_;
  const double descent = std::max(0.0, state_->p_W.z() - ground);
  return config_.battery.return_margin * (way / config_.follower.max_speed + descent / config_.land_speed) +
         config_.battery.return_overhead;
}

FlightController::TakeoffClimb FlightController::takeoffClimb(double altitude, const Vector3& from) const
{
  std::ostringstream why;
  if (!std::isfinite(altitude) || altitude < 0.0) {
    why << "takeoff refused: altitude " << altitude << " m is not a height above the take-off point";
    return {0.0, why.str()};
  }
  double up = altitude > 0.0 ? altitude : config_.takeoff_altitude;
  if (altitude == 0.0) {
    // The configured altitude is a default: under a low ceiling (a room), climb less. The
    // ceilings: the geofence's, and the one the upward rangefinder measured over the vehicle.
    struct Ceiling {
      double room;  // [m] to climb under it, less the margin
      std::string what;
    };
    std::vector<Ceiling> ceilings;
    if (config_.geofence.max[2] < common::Geofence::kUnbounded) {
      std::ostringstream what;
      what << "the geofence's ceiling at " << config_.geofence.max[2] << " m";
      ceilings.push_back({config_.geofence.max[2] - config_.takeoff_ceiling_margin - from.z(), what.str()});
    }
    if (std::isfinite(overhead_)) {
      std::ostringstream what;
      what << "the ceiling measured " << overhead_ << " m above";
      ceilings.push_back({overhead_ - config_.takeoff_ceiling_margin, what.str()});
    }
    for (const Ceiling& c : ceilings) {
      if (c.room <= config_.land_detector.ground_clearance) {
        why << "takeoff refused: " << c.what << " leaves " << c.room << " m to climb (takeoff_ceiling_margin "
            << config_.takeoff_ceiling_margin << " m under it), too little to leave the ground "
            << "(land_detector.ground_clearance " << config_.land_detector.ground_clearance << " m)";
        return {0.0, why.str()};
      }
      up = std::min(up, c.room);
    }
  }
  if (!config_.geofence.contains(Vector3(from + up * Vector3::UnitZ()))) {
    why << "takeoff refused: " << up << " m up would leave the geofence";
    return {0.0, why.str()};
  }
  return {up, ""};
}

bool FlightController::onGoal(const Vector3& p, double tolerance, bool land)
{
  if (!p.allFinite() || !std::isfinite(tolerance)) {
    ++rejected_;
    return false;
  }
  goal_ = p;
  goal_tolerance_ = tolerance > 0.0 ? tolerance : config_.goal_tolerance;
  land_at_goal_ = land;
  return true;
}

void FlightController::enter(Mode from, Mode mode, double t, const std::optional<VehicleState>& state)
{
  const Vector3 p = state ? state->p_W : Vector3::Zero();
  const double yaw = state ? yawOf(state->q_WB) : 0.0;
  switch (mode) {
    case Mode::kDisarmed:
    case Mode::kIdle:
      follower_.hold(p, yaw, t);
      controller_.reset();
      break;
    case Mode::kTakeoff:
      follower_.hold(p, yaw, t);
      takeoff_altitude_ = takeoffClimb(pending_altitude_, p).up;
      takeoff_target_ = p + Vector3(0.0, 0.0, takeoff_altitude_);
      follower_.setPath({p, takeoff_target_}, 0, t);
      flown_ = {takeoff_target_};
      flown_length_ = 0.0;
      break;
    case Mode::kReturn:
      // Back along the flown path: the one way known to be clear (the world stands still).
      // Taken from the reference; turning back from full speed is not within the limits, so
      // the vehicle brakes first and update() tries again while the follower refuses it.
      return_path_ = {p};
      return_path_.insert(return_path_.end(), flown_.rbegin(), flown_.rend());
      return_pending_ = !follower_.setPath(return_path_, 0, t);
      if (return_pending_) {
        follower_.brake(t);
      }
      path_retry_t_ = t + kPathRetryPeriod;
      break;
    case Mode::kHover: {
      // Hold where the reference is, unless the vehicle is far from it (after a failsafe), or
      // the controller has just taken over in the air: its reference is nobody's yet.
      if (from == Mode::kDisarmed) {
        follower_.hold(p, yaw, t);
        break;
      }
      // Moving (a mission or a way back stopped, or the state gone stale on the way): brake
      // along the trajectory flown, as hard as its limits allow, to rest in space it was made
      // for; not a point passed, which the vehicle would fly back to.
      if (follower_.reference().v_W.norm() > 0.05) {
        follower_.brake(t);
        break;
      }
      const Vector3 hold = (follower_.reference().p_W - p).norm() < 1.0 ? follower_.reference().p_W : p;
      follower_.hold(hold, follower_.reference().yaw, t);
      break;
    }
    case Mode::kMission:
      path_changed_ = !follower_.setPath(flyablePath(), path_version_.value_or(0), t);
      path_retry_t_ = t + kPathRetryPeriod;
      break;
    case Mode::kLand:
    case Mode::kFailsafeLand:
      land_xy_ = p;
      land_z0_ = std::min(p.z(), follower_.reference().p_W.z());
      land_t0_ = t;
      break;
  }
}

FlightOutput FlightController::update(double t)
{
  FlightOutput out;
  const double dt = last_update_t_ < 0.0 ? 0.0 : std::clamp(t - last_update_t_, 0.0, 0.1);
  last_update_t_ = t;

  ModeInputs in;
  in.t = t;
  in.command = pending_;
  pending_ = Command::kNone;
  const std::string takeoff_refused =
      in.command == Command::kTakeoff && state_ ? takeoffClimb(pending_altitude_, state_->p_W).refused : "";
  if (!takeoff_refused.empty()) {
    in.command = Command::kNone;
  }
  in.state_fresh = state_ && !state_late_ && t - state_t_ <= config_.state_timeout;
  const bool path_heard = t - path_t_ <= config_.path_timeout;
  in.path_fresh = path_kind_ == PathKind::kOk && path_version_ && path_heard && !path_late_;
  in.no_path = path_kind_ == PathKind::kUnreachable && path_heard;
  if (judge_landing_ && in.state_fresh) {
    landed_ = land_detector_.update(t, modes_.mode(), *state_, thrust_ratio_);
  } else if (judge_landing_ && imu_ && t - imu_t_ <= config_.state_timeout) {
    landed_ = land_detector_.update(t, modes_.mode(), *imu_, thrust_ratio_);  // blind: the IMU alone
  }
  in.landed = landed_;
  in.landing_judged = !judge_landing_ || land_detector_.judged();
  in.estimate_uncertain = !notes_.covariance_ok;
  in.takeoff_altitude_reached = modes_.mode() == Mode::kTakeoff && state_ && follower_.finished(t) &&
                                std::abs(state_->p_W.z() - takeoff_target_.z()) < 0.1;
  // At the goal: within tolerance, and (in a mission) at the end of the path. Outside a
  // mission this keeps auto_mission from starting again for a goal already reached.
  in.goal_reached = state_ && goal_ && (state_->p_W - *goal_).norm() <= goal_tolerance_ &&
                    (modes_.mode() != Mode::kMission || follower_.finished(t));
  in.land_at_goal = land_at_goal_;
  in.returned = modes_.mode() == Mode::kReturn && !return_pending_ && follower_.finished(t);
  if (state_) {
    // Taking off from a floor at the ground, an estimate a centimetre below it is no breach.
    Vector3 p = state_->p_W;
    if (modes_.mode() == Mode::kTakeoff) {
      p.z() = std::max(p.z(), config_.geofence.min[2]);
    }
    in.outside_geofence = !config_.geofence.contains(p);
  }
  if (state_ && (modes_.mode() == Mode::kMission || modes_.mode() == Mode::kHover) &&
      (flown_.empty() || (state_->p_W - flown_.back()).norm() >= kBreadcrumbSpacing)) {
    flown_length_ += flown_.empty() ? 0.0 : (state_->p_W - flown_.back()).norm();
    flown_.push_back(state_->p_W);
  }
  in.link_lost = operator_t_ && config_.link_loss_after > 0.0 && t - *operator_t_ > config_.link_loss_after;
  if (battery_) {
    const BatteryPolicy& policy = config_.battery;
    in.battery_low = battery_->charge <= policy.reserve || batteryTimeLeft() <= returnTime();
    in.battery_critical = battery_->charge <= policy.critical ||
                          (cells_low_since_ >= 0.0 && battery_t_ - cells_low_since_ >= policy.critical_after);
  }
  // The last state carried to now by the IMU samples since (the state itself when none came
  // after it). Closing the loops on a state frozen at its last value would pitch the vehicle
  // over in the moments before it counts as stale. Once stale, only up to the horizon.
  const std::optional<VehicleState> state = reckoning_.estimate(
      t, config_.state_timeout, in.state_fresh ? config_.state_timeout : config_.dead_reckoning_horizon);
  in.dead_reckoning = !in.state_fresh && state.has_value();
  out.transition = modes_.update(in);
  out.refused = takeoff_refused.empty() ? modes_.refused() : takeoff_refused;
  if (!takeoff_refused.empty() || in.command != Command::kNone) {
    out.answer = answerTo(takeoff_refused.empty() ? in.command : Command::kTakeoff, out.transition, out.refused,
                          modes_.mode());
  }
  if (out.transition) {
    enter(out.transition->from, out.transition->to, t, state ? state : state_);
  }
  out.mode = modes_.mode();
  out.reason = modes_.reason();
  out.camera = camera_;  // held where no loop runs
  // A replan (or the way back) is flown from the reference, without a jump. One the follower
  // refused (no trajectory within the limits from there: a turn too sharp for the speed) is
  // tried again a little later, from wherever the trajectory it kept has taken the reference
  // (it stops there at the latest).
  const bool retry = t >= path_retry_t_;
  if (out.mode == Mode::kMission && path_changed_ && retry) {
    path_changed_ = !follower_.setPath(flyablePath(), path_version_.value_or(0), t);
    // Tried again soon, then less often while it keeps being refused (a new path: at once).
    path_retry_period_ = path_changed_ ? std::min(2.0 * path_retry_period_, kPathRetryLongest) : kPathRetryPeriod;
    path_retry_t_ = t + path_retry_period_;
    // The planner saw what the trajectory flown was not made for: stop along it (the backup,
    // FASTER's), and take the newest path as soon as the slower reference allows it.
    if (path_changed_ && braking_for_ != path_version_) {
      braking_for_ = path_version_;
      follower_.brake(t);
    }
  } else if (out.mode == Mode::kReturn && return_pending_ && retry) {
    return_pending_ = !follower_.setPath(return_path_, 0, t);
    path_retry_t_ = t + kPathRetryPeriod;
  }

  switch (out.mode) {
    case Mode::kDisarmed:
      out.armed = false;
      thrust_ratio_ = 0.0;
      return out;
    case Mode::kIdle:
      out.armed = true;  // rotors at their minimum speed on the ground
      out.rotor_speed.fill(vehicle_.rotor_speed_min);
      thrust_ratio_ = 0.0;
      return out;
    default:
      break;
  }
  out.armed = true;
  if (!state) {
    // Blind: no state to close any loop on. Descend on a little less than the weight.
    const MixerOutput m = mixer_.mix(config_.failsafe_thrust * vehicle_.mass * 9.81, Vector3::Zero());
    thrust_ratio_ = config_.failsafe_thrust;
    out.rotor_speed = m.rotor_speed;
    out.mixer = m;
    return out;
  }
  Reference ref;
  if (out.mode == Mode::kLand || out.mode == Mode::kFailsafeLand) {
    // Straight down at the landing speed, aiming a little below the ground to touch down.
    const double z = std::max(-0.3, land_z0_ - config_.land_speed * (t - land_t0_));
    ref.p_W = Vector3(land_xy_.x(), land_xy_.y(), z);
    ref.v_W = Vector3(0.0, 0.0, z > -0.3 ? -config_.land_speed : 0.0);
    ref.yaw = follower_.reference().yaw;
  } else {
    ref = follower_.step(t);
    out.progress = follower_.progress();
  }
  out.reference = ref;
  out.trajectories = follower_.taken();
  aimCamera(out.mode, state->p_W);
  out.camera = camera_;
  out.dead_reckoning = !in.state_fresh;
  // The position error is the model's (a mass off its file, wind) only in the air, flying
  // a reference the vehicle can keep: not on the ground, taking off or landing.
  const bool flying = out.mode == Mode::kHover || out.mode == Mode::kMission || out.mode == Mode::kReturn;
  controller_.integrate(flying && !landed_);
  out.control = controller_.update(*state, ref, dt);
  if (!out.control.valid) {
    ++rejected_;
  }
  out.mixer = mixer_.mix(out.control.thrust, out.control.torque_B);
  thrust_ratio_ = out.control.thrust / (vehicle_.mass * 9.81);
  out.rotor_speed = out.mixer.rotor_speed;
  out.position_error_W = ref.p_W - state->p_W;
  out.velocity_error_W = ref.v_W - state->v_W;
  return out;
}

}  // namespace quad::control
