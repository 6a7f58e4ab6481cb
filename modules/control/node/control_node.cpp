// SPDX-License-Identifier: BSD-3-Clause
#include "control_node.hpp"

#include <limits>

#include <spdlog/spdlog.h>

#include "conversions.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/trajectory_messages.hpp"

namespace quad::control {

namespace {
constexpr std::int64_t kTickNs = 20'000'000;  // watch for a silent plant at 50 Hz
/// [s] The tick's own judgement of a silent plant waits this much past the state's timeout: the
/// state topic's deadline event (at the timeout) comes first, and the tick stands behind it.
constexpr double kTickBackstopS = 0.04;
/// [s] A deadline event for a topic one of whose samples was taken this recently is older than
/// that sample (the middleware timed it from before it): not acted on.
constexpr double kDeadlineEventSlackS = 0.01;

/// The same state sent again: every member equal (a NaN never is).
bool sameState(const runtime::StateSample& a, const runtime::StateSample& b)
{
  return a.aligned == b.aligned && a.p_W == b.p_W && a.v_W == b.v_W && a.w_B == b.w_B && a.q_WB.w == b.q_WB.w &&
         a.q_WB.x == b.q_WB.x && a.q_WB.y == b.q_WB.y && a.q_WB.z == b.q_WB.z && a.landed == b.landed &&
         a.covariance_ok == b.covariance_ok && a.accel_bias_B == b.accel_bias_B && a.gyro_bias_B == b.gyro_bias_B;
}
}

ControlNode::ControlNode(ControlNodeConfig config, dds::Participant handle)
    : Node("control", std::move(handle)),
      config_(std::move(config)),
      fc_(vehicle::loadVehicle(config_.vehicle_file), config_.flight),
      autostart_(config_.autostart),
      state_(participant(), config_.state_source, waker()),
      path_(participant(), dds::topics::kPath, waker()),
      goal_(participant(), dds::topics::kGoal, waker()),
      command_(participant(), dds::topics::kVehicleCommand, waker()),
      imu_(participant(), dds::topics::kSimImu, waker()),
      battery_(participant(), dds::topics::kSimBattery, waker()),
      range_(participant(), dds::topics::kSimRange, waker()),
      range_up_(participant(), dds::topics::kSimRangeUp, waker()),
      operator_(participant(), dds::topics::kOperatorHeartbeat, waker()),
      actuators_(participant(), dds::topics::kActuators),
      status_(participant(), dds::topics::kControlStatus),
      reference_(participant(), dds::topics::kControlReference),
      trajectory_(participant(), dds::topics::kTrajectory),
      acks_(participant(), dds::topics::kCommandAck)
{
  setTickPeriod(kTickNs);
  followSimClock();
  setWakeOnReceipt(true);  // each round's state is answered on the thread that received it
  spdlog::info("control: vehicle {}, autostart {}, flying on the {} ({})", config_.vehicle_file.string(),
               config_.autostart, runtime::toString(config_.state_source), state_.topic().name);
}

void ControlNode::takeInputs()
{
  takeDueAfterStamp(imu_, imu_due_, [this](const msg::Imu& m) { applyImu(m); });
  takeDueAfterStamp(battery_, battery_due_, [this](const msg::BatteryState& b) { applyBattery(b); });
  takeDueAfterStamp(range_, range_due_, [this](const msg::Range& r) { applyRange(r); });
  takeDueAfterStamp(range_up_, range_up_due_, [this](const msg::Range& r) { applyRangeUp(r); });
  while (auto h = operator_.take()) {
    counters().samples_in++;
    if (!fc_.onOperatorHeartbeat(common::toSeconds(h->header().stamp_ns()))) {
      counters().errors++;
    }
  }
  while (auto c = command_.take()) {
    counters().samples_in++;
    const Command command = fromMessage(c->kind());
    if (command == Command::kNone) {
      continue;  // another module's (the mapper's save)
    }
    spdlog::info("control: command {} ({}), id {}", static_cast<int>(c->kind()), toString(command), c->command_id());
    if (c->command_id() == 0) {
      counters().errors++;
      acknowledge({0, c->kind(), command, c->altitude()},
                  {command, false, std::string(toString(command)) + " refused: command_id 0 is invalid"}, fc_.mode(),
                  c->header().stamp_ns());
      continue;
    }
    commands_.hold(dds::topics::operatorInputDueNs(c->header().stamp_ns(), simClock().ns()),
                   {c->command_id(), c->kind(), command, c->altitude()});
  }
  // In lockstep a path, goal or command takes effect at a sim time fixed by its stamp, not
  // when it happens to arrive, so that runs repeat: a path with the first state after its
  // stamp, its due time (the planner's budget after the state it was planned on; the clock
  // waits there for a path not yet out, so it has come by then); an operator's goal or
  // command, whose station waits for no round, the contract's delay after its stamp.
  while (auto g = goal_.take()) {
    counters().samples_in++;
    if (lockstep()) {
      goals_due_.hold(dds::topics::operatorInputDueNs(g->header().stamp_ns(), simClock().ns()), std::move(*g));
    } else {
      applyGoal(*g);
    }
  }
  while (auto p = path_.take()) {
    counters().samples_in++;
    path_wall_ns_ = common::steadyTimeNs();
    if (lockstep()) {
      paths_due_.hold(runtime::dueAfter(p->header().stamp_ns()), std::move(*p));
    } else {
      applyPath(*p, latest_t_ >= 0.0 ? latest_t_ : common::toSeconds(p->header().stamp_ns()));
    }
  }
}

void ControlNode::applyPath(const msg::Path& p, double t)
{
  path_t_ = t;
  constexpr std::size_t kVersionsKept = 64;
  path_depth_ns_.insert_or_assign(p.version(), p.depth_stamp_ns());
  if (path_depth_ns_.size() > kVersionsKept) {
    path_depth_ns_.erase(path_depth_ns_.begin());
  }
  if (!fc_.onPath(waypointsOf(p), p.version(), pathKind(p.status()), t, p.known_free_m())) {
    counters().errors++;
    spdlog::warn("{}: version {} rejected: invalid waypoints or known-free length ({})", dds::topics::kPath.info.name,
                 p.version(), p.known_free_m());
  }
}

void ControlNode::applyImu(const msg::Imu& m)
{
  const double t = common::toSeconds(m.header().stamp_ns());
  if (!fc_.onImu({dds::toVector(m.specific_force_B()), dds::toVector(m.angular_rate_B())}, t)) {
    counters().errors++;
    spdlog::warn("{}: sample seq {} rejected: non-finite", dds::topics::kSimImu.info.name, m.header().seq());
    return;
  }
  imu_ns_ = std::max(imu_ns_, m.header().stamp_ns());
}

void ControlNode::applyRange(const msg::Range& r)
{
  checkRange(r, dds::topics::kSimRange.info.name,
             fc_.onRange(r.range(), r.max_range(), common::toSeconds(r.header().stamp_ns())));
}

void ControlNode::applyRangeUp(const msg::Range& r)
{
  checkRange(r, dds::topics::kSimRangeUp.info.name,
             fc_.onRangeUp(r.range(), r.max_range(), common::toSeconds(r.header().stamp_ns())));
}

void ControlNode::checkRange(const msg::Range& r, std::string_view topic, bool accepted)
{
  if (!accepted) {
    counters().errors++;
    spdlog::warn("{}: sample seq {} rejected: range {} m, max_range {} m", topic, r.header().seq(), r.range(),
                 r.max_range());
  }
}

void ControlNode::applyBattery(const msg::BatteryState& b)
{
  const BatteryReading reading{b.voltage(), b.current(), b.charge(), b.capacity(), b.cells()};
  if (!fc_.onBattery(reading, common::toSeconds(b.header().stamp_ns()))) {
    counters().errors++;
    spdlog::warn("{}: sample seq {} rejected: voltage {} V, current {} A, charge {}, capacity {} Ah, {} cells",
                 dds::topics::kSimBattery.info.name, b.header().seq(), b.voltage(), b.current(), b.charge(),
                 b.capacity(), b.cells());
  }
}

void ControlNode::applySensorsBefore(std::int64_t stamp_ns)
{
  imu_due_.release(stamp_ns, [this](const msg::Imu& m) { applyImu(m); });
  battery_due_.release(stamp_ns, [this](const msg::BatteryState& b) { applyBattery(b); });
  range_due_.release(stamp_ns, [this](const msg::Range& r) { applyRange(r); });
  range_up_due_.release(stamp_ns, [this](const msg::Range& r) { applyRangeUp(r); });
}

void ControlNode::applyGoal(const msg::Goal& g)
{
  if (!fc_.onGoal(dds::toVector(g.p_W()), g.tolerance(), g.land())) {
    counters().errors++;
    spdlog::warn("{}: goal {} rejected: non-finite", dds::topics::kGoal.info.name, g.goal_id());
  }
}

void ControlNode::applyDueInputs(std::int64_t stamp_ns)
{
  goals_due_.release(stamp_ns, [this](const msg::Goal& g) { applyGoal(g); });
  paths_due_.release(stamp_ns, [&](const msg::Path& p) { applyPath(p, common::toSeconds(stamp_ns)); });
}

void ControlNode::control(double t, std::int64_t stamp_ns)
{
  const std::optional<Command> autostart = autostart_.next(fc_.mode());
  if (autostart) {
    fc_.onCommand(*autostart);
  }
  applyDueInputs(stamp_ns);
  // One command a tick, each answered by it; out of lockstep as soon as it is taken.
  applying_ = commands_.releaseOne(lockstep() ? stamp_ns : std::numeric_limits<std::int64_t>::max());
  if (applying_) {
    fc_.onCommand(applying_->command, applying_->takeoff_altitude);
  }
  const bool autostart_only = autostart && !applying_;  // no operator's command this tick
  const FlightOutput out = fc_.update(t);
  if (applying_ && out.answer) {
    acknowledge(*applying_, *out.answer, out.mode, stamp_ns);
  }
  applying_.reset();
  msg::ActuatorCommand cmd;
  cmd.header().stamp_ns(stamp_ns);
  cmd.rotor_speed({out.rotor_speed[0], out.rotor_speed[1], out.rotor_speed[2], out.rotor_speed[3]});
  cmd.armed(out.armed);
  cmd.gimbal_yaw_W(out.camera.yaw_W);
  cmd.gimbal_pitch(out.camera.pitch);
  actuators_.write(cmd);
  answered_ns_ = stamp_ns;
  answer_ = cmd;
  msg::ControlReference ref = toMessage(out.reference, out.progress);
  ref.header().stamp_ns(stamp_ns);
  reference_.write(ref);
  counters().samples_out += 2;
  const TrajectoryFollower& follower = fc_.follower();
  if (follower.refused() > refused_ && fc_.pathVersion() != refused_version_) {
    // A path the follower cannot fly from where the reference is (it flies on what it has, a
    // trajectory that ends at rest, and tries again): once a path, not at every try.
    refused_version_ = fc_.pathVersion();
    spdlog::info("control: path {} not taken yet at {:.3f} s: {}", fc_.pathVersion().value_or(0), t,
                 follower.lastRefusal());
  }
  refused_ = follower.refused();
  if (out.trajectories != last_.trajectories) {
    // What is flown from now on, whole: a replan taken, a stop, a hold.
    msg::Trajectory m = dds::toMessage(follower.trajectory(), out.trajectories, follower.version().value_or(0));
    const auto depth = path_depth_ns_.find(follower.version().value_or(0));
    m.depth_stamp_ns(follower.version() && depth != path_depth_ns_.end() ? depth->second : -1);
    m.header().stamp_ns(stamp_ns);
    trajectory_.write(m);
    counters().samples_out++;
  }
  if (out.transition) {
    spdlog::info("control: {} -> {}: {}", toString(out.transition->from), toString(out.transition->to),
                 out.transition->why);
  }
  if (out.dead_reckoning && !last_.dead_reckoning) {
    spdlog::info("control: state stale at {:.3f} s: flying on the IMU's dead reckoning", t);
  } else if (last_.dead_reckoning && !out.dead_reckoning) {
    spdlog::info("control: dead reckoning ended at {:.3f} s", t);
  }
  if (!out.refused.empty()) {
    // The autostart asks again every tick until its command takes (while the first state is
    // not yet fresh, say): each reason it is refused for is worth a line once, not per tick.
    if (autostart_only && !autostart_.newRefusal(out.refused)) {
      spdlog::debug("control: {} (the autostart asks again)", out.refused);
    } else {
      spdlog::warn("control: {}", out.refused);
    }
  }
  if (out.transition || t >= next_status_t_) {
    publishStatus(out, stamp_ns);
    next_status_t_ = t + 1.0 / config_.status_rate;
  }
  last_ = out;
}

void ControlNode::publishStatus(const FlightOutput& out, std::int64_t stamp_ns)
{
  msg::ControlStatus s;
  s.header().stamp_ns(stamp_ns);
  s.mode(toMessage(out.mode));
  s.failsafe_reason(toMessage(out.reason));
  s.position_error_W(dds::toMessage(out.position_error_W));
  s.velocity_error_W(dds::toMessage(out.velocity_error_W));
  s.attitude_error(out.control.attitude_error);
  s.path_version(fc_.pathVersion().value_or(0));
  s.saturated(out.mixer.saturated);
  s.rejected_inputs(fc_.rejectedInputs());
  status_.write(s);
}

void ControlNode::acknowledge(const QueuedCommand& command, const CommandAnswer& answer, Mode mode,
                              std::int64_t stamp_ns)
{
  msg::CommandAck ack;
  ack.header().stamp_ns(stamp_ns);
  ack.command_id(command.id);
  ack.kind(command.kind);
  ack.accepted(answer.accepted);
  ack.mode(toMessage(mode));
  ack.reason(answer.reason.substr(0, 256));
  acks_.write(ack);
  counters().samples_out++;
  spdlog::info("control: command {} {}: {}", ack.command_id(), answer.accepted ? "taken" : "refused", answer.reason);
}

void ControlNode::onWake()
{
  takeInputs();
  for (const auto& s : state_.takeAll()) {
    counters().samples_in++;
    const double t = common::toSeconds(s.stamp_ns);
    if (lockstep() && answered_state_ && s.stamp_ns == answered_ns_ && sameState(s, *answered_state_)) {
      // Sent again by a plant still waiting for the round: the answer it may have lost, again.
      actuators_.write(answer_);
      counters().samples_out++;
      continue;
    }
    if (simClock().seen() && !simClock().vouchesFor(s.stamp_ns)) {
      // Accepted, it would make every state after it look out of order.
      counters().errors++;
      fc_.countRejected();
      spdlog::warn("{}: sample seq {} rejected: stamped {:.3f} s, ahead of the sim clock ({:.3f} s)",
                   state_.topic().name, s.seq, t, common::toSeconds(simClock().ns()));
      continue;
    }
    applySensorsBefore(s.stamp_ns);
    if (!s.aligned) {
      // An estimator still aligning: nothing to fly on yet, but in lockstep the round waits
      // for the answer to its time (the rotors stay as the mode has them).
      if (lockstep() && s.stamp_ns > answered_ns_) {
        control(t, s.stamp_ns);
        answered_state_ = s;
      }
      continue;
    }
    if (!fc_.onState(fromSample(s), t, {s.landed, s.covariance_ok, s.accel_bias_B, s.gyro_bias_B})) {
      counters().errors++;
      spdlog::warn("{}: sample seq {} rejected: invalid or out of order", state_.topic().name, s.seq);
      continue;
    }
    latest_t_ = t;
    latest_wall_ns_ = common::steadyTimeNs();
    control(t, s.stamp_ns);
    answered_state_ = s;
  }
  controlWithoutState();
}

void ControlNode::controlWithoutState()
{
  // When the states stop coming the controller must still fly, on the IMU's dead reckoning,
  // and reach its failsafe. In lockstep only a fault drops them, and the clock says so
  // (SimClock.state_sent): every such round is answered at the clock's time, and the plant
  // waits for that answer as for a state's, so that the vehicle is flown without lag and runs
  // repeat. A round whose state was sent is answered by that state only, however stale the
  // last one is (the first round after an outage): its clock sample may be handled before
  // its state comes or after, and answering it twice, on dead reckoning and on the state,
  // would let whichever answer reached the plant first fly the round. In real time, once the
  // state is stale, at the IMU samples' time.
  const std::int64_t now_ns = lockstep() ? simClock().ns() : imu_ns_;
  if (now_ns <= last_stateless_ns_ || now_ns <= answered_ns_) {
    return;
  }
  const double t = common::toSeconds(now_ns);
  const bool dropped = lockstep() && !simClock().stateSentAt(now_ns);
  const bool stale = latest_t_ >= 0.0 && t - latest_t_ > config_.flight.state_timeout;
  if (lockstep() ? dropped : stale) {
    last_stateless_ns_ = now_ns;
    applySensorsBefore(now_ns);
    control(t, now_ns);
    answered_state_.reset();
  }
}

void ControlNode::onTick(std::int64_t /*steady_ns*/)
{
  takeInputs();
  controlSilentPlant(config_.flight.state_timeout + kTickBackstopS);
}

void ControlNode::controlSilentPlant(double after_s)
{
  // In real time, states that stop while the plant's clock runs on (a sensor's outage, a lost
  // estimator, a link that drops them) must still reach the failsafe: fly it at the clock's
  // time. A clock that stops with them is the simulator falling behind (starved, stopped): the
  // vehicle's time stands still with it, nothing went stale in it, and the controller waits.
  // (A controller cut off from a running plant is the plant's to judge: it holds a late
  // command only briefly, docs/plant.md.) In lockstep the plant waits for the controller.
  if (!simClock().seen() || lockstep() || latest_t_ < 0.0) {
    return;  // (until a clock says which, a quiet plant may be a lockstep one waiting for us)
  }
  const std::int64_t heard_ns = std::max(common::toNanoseconds(latest_t_), imu_ns_);
  const std::int64_t clock_ns = simClock().ns();
  if (common::toSeconds(clock_ns - heard_ns) > after_s) {
    control(common::toSeconds(clock_ns), clock_ns);
  }
}

void ControlNode::onEvent(const dds::EndpointEvent& event)
{
  Node::onEvent(event);
  // Wall-clock deadlines say nothing in lockstep, where sim time waits for every module.
  if (event.kind != dds::EventKind::kDeadlineMissed || lockstep() || !simClock().seen()) {
    return;
  }
  // A timeout set longer than the contract's (timeouts.* in the config, for hand-fed inputs)
  // is the operator's word: the contract's deadline event then says nothing.
  const auto judged = [](double timeout, const dds::TopicInfo& topic) { return timeout <= topic.stale_after_s + 1e-9; };
  // A deadline is missed in wall time; it counts once the plant's clock, the vehicle's time,
  // has run past it too: a plant behind real time slows its clock and starves nobody.
  const std::int64_t now = common::steadyTimeNs();
  const double clock_t = common::toSeconds(simClock().ns());
  const auto late = [&](std::int64_t taken_wall_ns, double taken_t, const dds::TopicInfo& topic) {
    const double slack = topic.stale_after_s - kDeadlineEventSlackS;
    return common::toSeconds(now - taken_wall_ns) >= slack && clock_t - taken_t >= slack;
  };
  if (event.topic == state_.topic().name && latest_t_ >= 0.0 && judged(config_.flight.state_timeout, state_.topic())) {
    if (late(latest_wall_ns_, latest_t_, state_.topic())) {
      fc_.onStateLate();
      controlSilentPlant(0.0);  // the failsafe's tick, now
    }
  } else if (event.topic == dds::topics::kPath.info.name && judged(config_.flight.path_timeout, dds::topics::kPath.info) &&
             path_t_ >= 0.0 && late(path_wall_ns_, path_t_, dds::topics::kPath.info)) {
    fc_.onPathLate();
  }
}

runtime::ModuleEntry controlModule() { return runtime::moduleEntry<ControlNode>("control", controlSchema(), controlConfigFrom); }

}  // namespace quad::control
