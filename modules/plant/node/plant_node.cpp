// SPDX-License-Identifier: BSD-3-Clause
#include "plant_node.hpp"

#include <spdlog/spdlog.h>

#include "conversions.hpp"
#include "quad/dds/fault_messages.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/common/time.hpp"
#include "quad/world/world_file.hpp"

namespace quad::plant {

namespace {
constexpr std::int64_t kRealTimeTickNs = 1'000'000;      // pace in 1 ms slices
constexpr std::int64_t kBehindReportNs = 100'000'000;    // a lag worth a line in the log
constexpr std::int64_t kRepublishNs = 20'000'000;        // lockstep: resend a round's state this often
std::string verdictText(CommandGuard::Verdict v)
{
  switch (v) {
    case CommandGuard::Verdict::kAccepted:
      return "accepted";
    case CommandGuard::Verdict::kClamped:
      return "clamped to the rotor limits";
    case CommandGuard::Verdict::kRejectedInvalid:
      return "rejected: non-finite speed";
    case CommandGuard::Verdict::kRejectedLate:
      return "rejected: late";
    case CommandGuard::Verdict::kRejectedOld:
      return "rejected: older than the command held";
  }
  return "?";
}
}  // namespace

PlantNode::PlantNode(PlantNodeConfig config, dds::ParticipantOptions options)
    : Node("plant", std::move(options)),
      config_(std::move(config)),
      sim_(std::make_unique<Simulation>(
          vehicle::loadVehicle(config_.vehicle_file), world::loadWorld(config_.world_file),
          config_.simulation,
          config_.fault_schedule_file.empty() ? std::vector<Fault>{}
                                              : loadFaultSchedule(config_.fault_schedule_file))),
      clock_(participant(), dds::topics::kSimClock),
      state_(participant(), dds::topics::kSimState),
      imu_(participant(), dds::topics::kSimImu),
      position_(participant(), dds::topics::kSimPosition),
      baro_(participant(), dds::topics::kSimBaro),
      mag_(participant(), dds::topics::kSimMag),
      battery_(participant(), dds::topics::kSimBattery),
      depth_(participant(), dds::topics::kSimDepth),
      events_(participant(), dds::topics::kSimEvents),
      actuators_(participant(), dds::topics::kActuators, waker()),
      faults_(participant(), dds::topics::kFault, waker())
{
  if (config_.mode == PlantNodeConfig::Mode::kLockstep && !config_.lockstep_participants.empty()) {
    barrier_ = std::make_unique<dds::LockstepBarrier>(participant(), config_.lockstep_participants, waker());
  }
  setTickPeriod(kRealTimeTickNs);
  setLockstep(config_.mode == PlantNodeConfig::Mode::kLockstep);
  spdlog::info("plant: vehicle {}, world {} ({} obstacles), {} mode, seed {}", config_.vehicle_file.string(),
               config_.world_file.string(), sim_->world().obstacles().size(),
               config_.mode == PlantNodeConfig::Mode::kLockstep ? "lockstep" : "real-time",
               config_.simulation.seed);
  const WindConfig& wind = config_.simulation.wind;
  if (!wind.steady_W.isZero() || wind.turbulence_w20 > 0.0) {
    spdlog::info("plant: wind ({:.1f}, {:.1f}, {:.1f}) m/s steady, turbulence {}", wind.steady_W.x(),
                 wind.steady_W.y(), wind.steady_W.z(),
                 wind.turbulence_w20 > 0.0 ? fmt::format("W20 {:.1f} m/s (Dryden, MIL-F-8785C)", wind.turbulence_w20)
                                           : std::string("none"));
  }
}

void PlantNode::event(msg::SimEventKind kind, std::int64_t subject, const std::string& detail)
{
  msg::SimEvent e;
  e.header().stamp_ns(sim_->timeNs());
  e.kind(kind);
  e.p_W(dds::toMessage(sim_->state().p_W));
  e.subject_id(subject);
  e.detail(detail.substr(0, 256));
  events_.write(e);
}

void PlantNode::onStart()
{
  wall_start_ns_ = common::steadyTimeNs();
  event(msg::SIM_EVENT_RUN_STARTED, -1, "plant started");
  publishClock();
  // The initial state, so that a controller can compute the first command.
  last_state_ = StateSample{0, sim_->state(), Vector3::Zero()};
  state_.write(toMessage(*last_state_));
  last_state_publish_ns_ = common::steadyTimeNs();
}

void PlantNode::takeInputs()
{
  while (auto cmd = actuators_.take()) {
    counters().samples_in++;
    if (config_.mode == PlantNodeConfig::Mode::kLockstep && cmd->header().stamp_ns() == latest_command_stamp_ns_) {
      continue;  // the answer to a state sent again, again
    }
    const RotorArray speeds{cmd->rotor_speed()[0], cmd->rotor_speed()[1], cmd->rotor_speed()[2],
                            cmd->rotor_speed()[3]};
    const auto verdict = sim_->commands().submit(speeds, cmd->armed(), cmd->header().stamp_ns(), sim_->timeNs());
    if (verdict == CommandGuard::Verdict::kAccepted || verdict == CommandGuard::Verdict::kClamped) {
      latest_command_stamp_ns_ = std::max(latest_command_stamp_ns_, cmd->header().stamp_ns());
      if (sim_->gimbal() && !sim_->aimGimbal(cmd->gimbal_yaw_W(), cmd->gimbal_pitch())) {
        counters().errors++;
        spdlog::warn("{}: command seq {}: gimbal yaw {} pitch {} not finite; the gimbal keeps its aim",
                     dds::topics::kActuators.info.name, cmd->header().seq(), cmd->gimbal_yaw_W(), cmd->gimbal_pitch());
      }
    }
    if (verdict != CommandGuard::Verdict::kAccepted) {
      counters().errors++;
      spdlog::warn("{}: command seq {} stamped {} ns {}", dds::topics::kActuators.info.name, cmd->header().seq(),
                   cmd->header().stamp_ns(), verdictText(verdict));
    }
  }
  while (auto fault = faults_.take()) {
    counters().samples_in++;
    const bool layer = participant().datagramFaults() != nullptr;
    if (fault->module_name().to_string() != "plant" || (layer && dds::isDatagramFault(fault->kind())) ||
        (fault->kind() == msg::FAULT_CLEAR && isDatagramFaultId(fault->fault_id()))) {
      continue;  // for another module, or for the node's datagram fault layer
    }
    if (fault->kind() == msg::FAULT_CLEAR) {
      if (!sim_->clearFault(fault->fault_id())) {
        event(msg::SIM_EVENT_FAULT_REJECTED, fault->fault_id(), "no fault " + std::to_string(fault->fault_id()) + " to clear");
      }
      continue;
    }
    std::string why_not;
    const auto core = faultFrom(*fault, sim_->timeNs(), why_not);
    if (!core || !sim_->injectFault(*core)) {
      const std::string reason = core ? "fault id already in use" : why_not;
      spdlog::warn("{}: fault {} rejected: {}", dds::topics::kFault.info.name, fault->fault_id(), reason);
      event(msg::SIM_EVENT_FAULT_REJECTED, fault->fault_id(), "fault " + std::to_string(fault->fault_id()) + " rejected: " + reason);
    }
  }
}

void PlantNode::publishClock()
{
  msg::SimClock clock;
  clock.header().stamp_ns(sim_->timeNs());
  clock.sim_ns(sim_->timeNs());
  clock.step_ns(config_.simulation.step_ns);
  clock.real_time_factor(config_.real_time_factor);
  clock.lockstep(config_.mode == PlantNodeConfig::Mode::kLockstep);
  clock.depth_frames(depth_frames_);
  clock.state_sent(answeredInputNs() == sim_->timeNs());
  clock_.write(clock);
}

std::int64_t PlantNode::answeredInputNs() const
{
  if (config_.state_source == dds::StateSource::kEstimate) {
    return last_imu_ ? last_imu_->header().stamp_ns() : -1;
  }
  return last_state_ ? last_state_->t_ns : -1;
}

void PlantNode::publish(const StepOutputs& out)
{
  // The battery before the state the controller steps on: its failsafe sees the pack as it
  // was at that state's time.
  if (out.battery) {
    battery_.write(toMessage(*out.battery));
    counters().samples_out++;
  }
  // Depth first: the clock that follows counts it.
  if (out.depth) {
    last_depth_ = toMessage(*out.depth, config_.simulation.depth.max_range);
    last_depth_->frame(++depth_frames_);
    depth_.write(*last_depth_);
    counters().samples_out++;
  }
  if (out.imu) {
    last_imu_ = toMessage(*out.imu);  // before the clock, which says whether it was sent
  }
  if (out.state) {
    last_state_ = out.state;
    last_state_publish_ns_ = common::steadyTimeNs();
    state_.write(toMessage(*out.state));
    counters().samples_out++;
  }
  if (out.state_due) {
    publishClock();  // at the state's rate (its contract's 250 Hz), even when a fault drops the state
    counters().samples_out++;
  }
  if (out.imu) {
    // The aids written before it, which a lockstep estimator answers it with (Imu.idl).
    last_imu_->position_seq(position_.lastSeq());
    last_imu_->baro_seq(baro_.lastSeq());
    last_imu_->mag_seq(mag_.lastSeq());
    imu_.write(*last_imu_);
    counters().samples_out++;
  }
  if (out.position) {
    position_.write(toMessage(*out.position));
    counters().samples_out++;
  }
  if (out.baro) {
    baro_.write(toMessage(*out.baro));
    counters().samples_out++;
  }
  if (out.mag) {
    mag_.write(toMessage(*out.mag));
    counters().samples_out++;
  }
  for (const auto& e : out.events) {
    events_.write(toMessage(e));
    if (e.kind == SimEventRecord::Kind::kCollision) {
      spdlog::warn("plant: collision at t = {:.3f} s: {}", common::toSeconds(e.t_ns), e.detail);
    } else {
      spdlog::info("plant: t = {:.3f} s: {}", common::toSeconds(e.t_ns), e.detail);
    }
  }
}

void PlantNode::stepOnce()
{
  publish(sim_->step());
  if (config_.duration_s > 0.0 && common::toSeconds(sim_->timeNs()) >= config_.duration_s) {
    spdlog::info("plant: sim time {:.3f} s reached its duration", common::toSeconds(sim_->timeNs()));
    stop();
  }
}

void PlantNode::runRealTime(std::int64_t steady_ns)
{
  const auto target = static_cast<std::int64_t>(
      static_cast<double>(steady_ns - wall_start_ns_) * config_.real_time_factor);
  const std::int64_t behind = target - sim_->timeNs() - static_cast<std::int64_t>(dropped_steps_) * config_.simulation.step_ns;
  // Behind the wall clock (a late wake, a starved or stopped process), the plant catches up
  // in a burst only as far as a held rotor command is flown whole: the controller cannot
  // answer steps run faster than real time, and a burst past that would fly the vehicle on
  // commands it no longer steers. Further behind, the clock slows instead: the lost time is
  // not simulated, and counted (the achieved factor is the run's sim time over its wall time).
  const std::int64_t max_catch_up = config_.simulation.command_failsafe_ns;
  if (behind > max_catch_up) {
    const std::int64_t skip = (behind - max_catch_up) / config_.simulation.step_ns;
    dropped_steps_ += static_cast<std::uint64_t>(skip);
    if (behind > kBehindReportNs) {
      spdlog::warn("plant: {:.3f} s behind real time; the clock slows by {} steps", common::toSeconds(behind), skip);
    }
  }
  while (!stopping() &&
         sim_->timeNs() + static_cast<std::int64_t>(dropped_steps_) * config_.simulation.step_ns < target) {
    stepOnce();
  }
}

void PlantNode::runLockstep()
{
  while (!stopping()) {
    if (!round_open_) {
      round_end_ns_ = sim_->timeNs() + config_.lockstep_period_ns;
      round_open_ = true;
      round_wait_since_ns_ = common::steadyTimeNs();
      next_wait_report_ns_ = round_wait_since_ns_ + common::toNanoseconds(config_.lockstep_timeout_s);
    }
    // A round may run once the controller answered the state of its start and every
    // participant finished its work up to then.
    const std::int64_t round_start = round_end_ns_ - config_.lockstep_period_ns;
    // The controller answers states (true ones, or the estimates of IMU samples): a round whose
    // input a fault dropped has nothing to answer.
    const bool state_sent = answeredInputNs() >= round_start;
    const bool command_ready =
        !config_.lockstep_wait_for_command || !state_sent || latest_command_stamp_ns_ >= round_start;
    const bool others_ready = !barrier_ || barrier_->poll(round_start);
    if (!command_ready || !others_ready) {
      const std::int64_t now = common::steadyTimeNs();
      if (now - last_state_publish_ns_ >= kRepublishNs) {
        // A state, clock or depth sample lost, or sent before a participant matched, would
        // stall the round for good. Resend them; an answer to a repeat is the same answer
        // (the mapper knows a cloud it has by its stamp).
        if (last_depth_) {
          depth_.write(*last_depth_);
        }
        if (last_state_ && last_state_->t_ns >= round_start) {
          state_.write(toMessage(*last_state_));
        }
        if (last_imu_ && last_imu_->header().stamp_ns() >= round_start) {
          imu_.write(*last_imu_);
        }
        publishClock();
        last_state_publish_ns_ = now;
      }
      if (now >= next_wait_report_ns_) {
        std::string late = command_ready ? "" : "control (no command for t = " + std::to_string(round_start) + " ns)";
        if (barrier_ && !others_ready) {
          for (const auto& l : barrier_->ledger().late(round_start)) {
            late += (late.empty() ? "" : ", ") + l;
          }
        }
        spdlog::warn("lockstep: at sim time {:.3f} s, still waiting after {:.1f} s for: {}",
                     common::toSeconds(round_start), common::toSeconds(now - round_wait_since_ns_), late);
        next_wait_report_ns_ = now + common::toNanoseconds(config_.lockstep_timeout_s);
      }
      return;  // woken again by commands or reports
    }
    while (!stopping() && sim_->timeNs() < round_end_ns_) {
      stepOnce();
    }
    round_open_ = false;
  }
}

void PlantNode::onWake()
{
  takeInputs();
  if (config_.mode == PlantNodeConfig::Mode::kLockstep) {
    runLockstep();
  }
}

void PlantNode::onTick(std::int64_t steady_ns)
{
  takeInputs();
  if (config_.mode == PlantNodeConfig::Mode::kRealTime) {
    runRealTime(steady_ns);
  } else {
    runLockstep();
  }
}

namespace {
constexpr std::chrono::milliseconds kFinalEventWait{2000};
}  // namespace

void PlantNode::onStop()
{
  const auto& c = sim_->commands().counters();
  const std::string summary =
      "sim time " + std::to_string(common::toSeconds(sim_->timeNs())) + " s, collisions " +
      std::to_string(sim_->collisionCount()) + ", commands accepted " + std::to_string(c.accepted) +
      ", clamped " + std::to_string(c.clamped) + ", rejected " +
      std::to_string(c.rejected_invalid + c.rejected_late + c.rejected_old) + ", stale steps " +
      std::to_string(c.stale_steps) + ", failsafe steps " + std::to_string(c.failsafe_steps) +
      ", dropped steps " + std::to_string(dropped_steps_);
  spdlog::info("plant: run ended: {}", summary);
  if (const auto& battery = sim_->battery()) {
    spdlog::info("plant: battery {:.1f} % left ({:.2f} of {:.2f} Ah), {:.1f} Wh drawn, {} of {} cells working",
                 100.0 * battery->charge(), battery->chargeAh(), battery->config().capacity,
                 battery->energyDrawn() / 3600.0, battery->workingCells(), battery->config().cells);
  }
  const auto& st = sim_->state();
  // Full precision, so that runs can be compared bit for bit from their logs.
  spdlog::info("plant: final state t {} ns p ({:.17g}, {:.17g}, {:.17g}) q ({:.17g}, {:.17g}, {:.17g}, {:.17g})",
               sim_->timeNs(), st.p_W.x(), st.p_W.y(), st.p_W.z(), st.q_WB.w, st.q_WB.x, st.q_WB.y, st.q_WB.z);
  event(msg::SIM_EVENT_RUN_ENDED, static_cast<std::int64_t>(sim_->collisionCount()), summary);
  // The run's last word (its final position and collisions) must reach the readers before
  // the participant goes: a reliable sample still unacknowledged at exit is lost.
  if (!events_.waitForAcknowledgments(kFinalEventWait)) {
    spdlog::warn("plant: {}: the run's end was not acknowledged by every reader within {} ms",
                 dds::topics::kSimEvents.info.name, kFinalEventWait.count());
  }
}

}  // namespace quad::plant
