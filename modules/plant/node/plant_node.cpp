// SPDX-License-Identifier: BSD-3-Clause
#include "plant_node.hpp"

#include <algorithm>

#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "conversions.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/fault_messages.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/plant/fleet_file.hpp"
#include "quad/world/world_file.hpp"

namespace quad::plant {

namespace {
constexpr std::int64_t kRealTimeTickNs = 1'000'000;      // pace in 1 ms slices
constexpr std::int64_t kBehindReportNs = 100'000'000;    // a lag worth a line in the log
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

/// The vehicles the plant simulates: its fleet file's, or the participant's own.
std::unique_ptr<Fleet> makeFleet(const PlantNodeConfig& config, std::uint32_t own_id)
{
  const world::World world = world::loadWorld(config.world_file);
  std::vector<FleetVehicle> vehicles;
  if (config.fleet_file.empty()) {
    vehicles.push_back({own_id, vehicle::loadVehicle(config.vehicle_file), world.start(), world.goal(),
                        config.fault_schedule_file.empty() ? std::vector<Fault>{}
                                                           : loadFaultSchedule(config.fault_schedule_file)});
  } else {
    if (!config.fault_schedule_file.empty()) {
      throw common::ConfigError({"faults.schedule: " + config.fault_schedule_file.string() +
                                 ": with a fleet file, each vehicle's schedule is its `faults` there"});
    }
    vehicles = loadFleet(config.fleet_file, world, config.vehicle_file);
    if (const auto why = Fleet::problem(vehicles)) {
      throw common::ConfigError({config.fleet_file.string() + ": " + *why});
    }
  }
  return std::make_unique<Fleet>(std::move(vehicles), world, config.simulation);
}

}  // namespace

PlantNode::PlantNode(PlantNodeConfig config, dds::Participant handle)
    : Node("plant", std::move(handle)),
      config_(std::move(config)),
      fleet_(makeFleet(config_, participant().options().vehicle_id)),
      clock_(participant(), dds::topics::kSimClock, fleet_->ids()),
      state_(participant(), dds::topics::kSimState, fleet_->ids()),
      imu_(participant(), dds::topics::kSimImu, fleet_->ids()),
      position_(participant(), dds::topics::kSimPosition, fleet_->ids()),
      baro_(participant(), dds::topics::kSimBaro, fleet_->ids()),
      mag_(participant(), dds::topics::kSimMag, fleet_->ids()),
      range_(participant(), dds::topics::kSimRange, fleet_->ids()),
      range_up_(participant(), dds::topics::kSimRangeUp, fleet_->ids()),
      battery_(participant(), dds::topics::kSimBattery, fleet_->ids()),
      depth_(participant(), dds::topics::kSimDepth, fleet_->ids()),
      events_(participant(), dds::topics::kSimEvents, fleet_->ids()),
      actuators_(participant(), dds::topics::kActuators, waker()),
      faults_(participant(), dds::topics::kFault, waker()),
      round_(config_.lockstep_period_ns, common::toNanoseconds(config_.lockstep_timeout_s))
{
  for (const std::uint32_t id : fleet_->ids()) {
    io_.push_back({.id = id});
  }
  std::vector<std::string> participants = config_.lockstep_participants;
  // The run's recorder and observer hold the first round until they read what this plant
  // writes: the recording and the run's summary then start with the run.
  const auto holdsStart = [&](bool holds, const char* name) {
    if (holds && std::find(participants.begin(), participants.end(), name) == participants.end()) {
      participants.emplace_back(name);
    }
  };
  holdsStart(participant().options().lockstep_recorder, runtime::kRecorderParticipant);
  holdsStart(participant().options().lockstep_observer, runtime::kObserverParticipant);
  if (config_.mode == PlantNodeConfig::Mode::kLockstep && !participants.empty()) {
    // With a fleet file each vehicle has its own participants (its mapper, its planner).
    barrier_ = std::make_unique<runtime::LockstepBarrier>(
        participant(), participants, waker(),
        config_.fleet_file.empty() ? std::vector<std::uint32_t>{} : fleet_->ids());
    // The mapper's work is the depth frames written here: between them it has none to hold the clock for.
    barrier_->worksOnInputsOnly(runtime::kMapperParticipant);
  }
  setTickPeriod(kRealTimeTickNs);
  setLockstep(config_.mode == PlantNodeConfig::Mode::kLockstep);
  const std::string vehicles =
      config_.fleet_file.empty()
          ? config_.vehicle_file.string()
          : fmt::format("{} vehicles ({}) from {}", io_.size(), fmt::join(fleet_->ids(), ", "),
                        config_.fleet_file.string());
  spdlog::info("plant: vehicle {}, world {} ({} obstacles), {} mode, seed {}", vehicles, config_.world_file.string(),
               simulation().world().obstacles().size(),
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

void PlantNode::event(std::size_t vehicle, msg::SimEventKind kind, std::int64_t subject, const std::string& detail)
{
  const Simulation& sim = fleet_->vehicle(vehicle);
  msg::SimEvent e;
  e.header().stamp_ns(sim.timeNs());
  e.kind(kind);
  e.p_W(dds::toMessage(sim.state().p_W));
  e.subject_id(subject);
  e.detail(detail.substr(0, 256));
  events_.writeFor(io_[vehicle].id, e);
}

void PlantNode::onStart()
{
  wall_start_ns_ = common::steadyTimeNs();
  for (std::size_t i = 0; i < io_.size(); ++i) {
    event(i, msg::SIM_EVENT_RUN_STARTED, -1, "plant started");
    publishClock(i);
    // The initial state, so that a controller can compute the first command.
    io_[i].last_state = StateSample{0, fleet_->vehicle(i).state(), Vector3::Zero()};
    state_.writeFor(io_[i].id, toMessage(*io_[i].last_state));
  }
  round_.published(common::steadyTimeNs());
}

void PlantNode::takeInputs()
{
  while (auto cmd = actuators_.takeServed(fleet_->ids())) {
    takeCommand(*fleet_->indexOf(cmd->header().vehicle_id()), *cmd);
  }
  while (auto fault = faults_.takeServed(fleet_->ids())) {
    takeFault(*fleet_->indexOf(fault->header().vehicle_id()), *fault);
  }
}

void PlantNode::takeCommand(std::size_t vehicle, const msg::ActuatorCommand& cmd)
{
  counters().samples_in++;
  VehicleIo& io = io_[vehicle];
  Simulation& sim = fleet_->vehicle(vehicle);
  if (config_.mode == PlantNodeConfig::Mode::kLockstep && cmd.header().stamp_ns() == io.latest_command_stamp_ns) {
    return;  // the answer to a state sent again, again
  }
  const RotorArray speeds{cmd.rotor_speed()[0], cmd.rotor_speed()[1], cmd.rotor_speed()[2], cmd.rotor_speed()[3]};
  const auto verdict = sim.commands().submit(speeds, cmd.armed(), cmd.header().stamp_ns(), sim.timeNs());
  if (verdict == CommandGuard::Verdict::kAccepted || verdict == CommandGuard::Verdict::kClamped) {
    io.latest_command_stamp_ns = std::max(io.latest_command_stamp_ns, cmd.header().stamp_ns());
    if (sim.gimbal() && !sim.aimGimbal(cmd.gimbal_yaw_W(), cmd.gimbal_pitch())) {
      counters().errors++;
      spdlog::warn("{}: command seq {}: gimbal yaw {} pitch {} not finite; the gimbal keeps its aim",
                   dds::topics::kActuators.info.name, cmd.header().seq(), cmd.gimbal_yaw_W(), cmd.gimbal_pitch());
    }
  }
  if (verdict != CommandGuard::Verdict::kAccepted) {
    counters().errors++;
    spdlog::warn("{}: command seq {} stamped {} ns {}", dds::topics::kActuators.info.name, cmd.header().seq(),
                 cmd.header().stamp_ns(), verdictText(verdict));
  }
}

void PlantNode::takeFault(std::size_t vehicle, const msg::FaultCommand& fault)
{
  counters().samples_in++;
  Simulation& sim = fleet_->vehicle(vehicle);
  const bool layer = participant().datagramFaults() != nullptr;
  if (fault.module_name().to_string() != "plant" || (layer && dds::isDatagramFault(fault.kind())) ||
      (fault.kind() == msg::FAULT_CLEAR && isDatagramFaultId(fault.fault_id()))) {
    return;  // for another module, or for the node's datagram fault layer
  }
  if (fault.kind() == msg::FAULT_CLEAR) {
    if (!sim.clearFault(fault.fault_id())) {
      event(vehicle, msg::SIM_EVENT_FAULT_REJECTED, fault.fault_id(),
            "no fault " + std::to_string(fault.fault_id()) + " to clear");
    }
    return;
  }
  std::string why_not;
  const auto core = faultFrom(fault, sim.timeNs(), why_not);
  if (!core || !sim.injectFault(*core)) {
    const std::string reason = core ? "fault id already in use" : why_not;
    spdlog::warn("{}: fault {} rejected: {}", dds::topics::kFault.info.name, fault.fault_id(), reason);
    event(vehicle, msg::SIM_EVENT_FAULT_REJECTED, fault.fault_id(),
          "fault " + std::to_string(fault.fault_id()) + " rejected: " + reason);
  }
}

void PlantNode::publishClock(std::size_t vehicle)
{
  // One clock sample per vehicle (the topic is keyed by it): each says what was sent to that
  // vehicle's modules up to now.
  const VehicleIo& io = io_[vehicle];
  msg::SimClock clock;
  clock.header().stamp_ns(fleet_->timeNs());
  clock.sim_ns(fleet_->timeNs());
  clock.step_ns(config_.simulation.step_ns);
  clock.real_time_factor(config_.real_time_factor);
  clock.lockstep(config_.mode == PlantNodeConfig::Mode::kLockstep);
  clock.depth_frames(io.depth_frames);
  clock.state_sent(answeredInputNs(io) == fleet_->timeNs());
  clock_.writeFor(io.id, clock);
}

std::int64_t PlantNode::answeredInputNs(const VehicleIo& io) const
{
  if (config_.state_source == runtime::StateSource::kEstimate) {
    return io.last_imu ? io.last_imu->header().stamp_ns() : -1;
  }
  return io.last_state ? io.last_state->t_ns : -1;
}

void PlantNode::publish(std::size_t vehicle, const StepOutputs& out)
{
  VehicleIo& io = io_[vehicle];
  // The battery before the state the controller steps on: its failsafe sees the pack as it
  // was at that state's time.
  if (out.battery) {
    battery_.writeFor(io.id, toMessage(*out.battery));
    counters().samples_out++;
  }
  // Depth first: the clock that follows counts it.
  if (out.depth) {
    io.last_depth = toMessage(*out.depth, config_.simulation.depth.max_range);
    io.last_depth->frame(++io.depth_frames);
    depth_.writeFor(io.id, *io.last_depth);
    counters().samples_out++;
    if (barrier_) {
      barrier_->inputGiven(runtime::kMapperParticipant, io.id,
                           io.last_depth->header().stamp_ns() + participant().options().mapBudgetNs());
    }
  }
  if (out.imu) {
    io.last_imu = toMessage(*out.imu);  // before the clock, which says whether it was sent
  }
  if (out.state) {
    io.last_state = out.state;
    round_.published(common::steadyTimeNs());
    state_.writeFor(io.id, toMessage(*out.state));
    counters().samples_out++;
  }
  if (out.state_due) {
    io.state_due_ns = fleet_->timeNs();
    publishClock(vehicle);  // at the state's rate (its contract's 250 Hz), even when a fault drops the state
    counters().samples_out++;
  }
  if (out.imu) {
    // The aids written before it, which a lockstep estimator answers it with (Imu.idl).
    io.last_imu->position_seq(position_.lastSeq(io.id));
    io.last_imu->baro_seq(baro_.lastSeq(io.id));
    io.last_imu->mag_seq(mag_.lastSeq(io.id));
    imu_.writeFor(io.id, *io.last_imu);
    counters().samples_out++;
  }
  if (out.position) {
    position_.writeFor(io.id, toMessage(*out.position));
    counters().samples_out++;
  }
  if (out.baro) {
    baro_.writeFor(io.id, toMessage(*out.baro));
    counters().samples_out++;
  }
  if (out.mag) {
    mag_.writeFor(io.id, toMessage(*out.mag));
    counters().samples_out++;
  }
  if (out.range) {
    range_.writeFor(io.id, toMessage(*out.range));
    counters().samples_out++;
  }
  if (out.range_up) {
    range_up_.writeFor(io.id, toMessage(*out.range_up));
    counters().samples_out++;
  }
  const std::string who = io_.size() > 1 ? fmt::format("vehicle {} ", io.id) : std::string();
  for (const auto& e : out.events) {
    events_.writeFor(io.id, toMessage(e));
    if (e.kind == SimEventRecord::Kind::kCollision) {
      spdlog::warn("plant: {}collision at t = {:.3f} s: {}", who, common::toSeconds(e.t_ns), e.detail);
    } else {
      spdlog::info("plant: {}t = {:.3f} s: {}", who, common::toSeconds(e.t_ns), e.detail);
    }
  }
}

void PlantNode::stepOnce()
{
  const std::vector<StepOutputs> out = fleet_->step();
  for (std::size_t i = 0; i < out.size(); ++i) {
    publish(i, out[i]);
  }
  if (config_.duration_s > 0.0 && common::toSeconds(fleet_->timeNs()) >= config_.duration_s) {
    spdlog::info("plant: sim time {:.3f} s reached its duration", common::toSeconds(fleet_->timeNs()));
    stop();
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (const auto& crash = fleet_->vehicle(i).crash(); crash && crash->t_ns == fleet_->timeNs()) {
      spdlog::warn("plant: {}crashed: the run ends", io_.size() > 1 ? fmt::format("vehicle {} ", io_[i].id) : std::string());
      stop();
    }
  }
}

void PlantNode::runRealTime(std::int64_t steady_ns)
{
  const auto target = static_cast<std::int64_t>(
      static_cast<double>(steady_ns - wall_start_ns_) * config_.real_time_factor);
  const std::int64_t behind = target - fleet_->timeNs() - static_cast<std::int64_t>(dropped_steps_) * config_.simulation.step_ns;
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
         fleet_->timeNs() + static_cast<std::int64_t>(dropped_steps_) * config_.simulation.step_ns < target) {
    stepOnce();
  }
}

void PlantNode::runLockstep()
{
  while (!stopping()) {
    // A round may run once every vehicle's controller answered the state of its start and
    // every participant finished its work up to then.
    const std::int64_t round_start = round_.open(fleet_->timeNs(), common::steadyTimeNs());
    // The controller answers states (true ones, or the estimates of IMU samples), and, once it
    // has answered one, a state's time whose input a fault dropped: the clock's sample of it
    // (on its dead reckoning).
    std::vector<std::uint32_t> unanswered;
    for (const VehicleIo& io : io_) {
      const bool owed = answeredInputNs(io) >= round_start ||
                        (io.state_due_ns == round_start && io.latest_command_stamp_ns >= 0);
      if (config_.lockstep_wait_for_command && owed && io.latest_command_stamp_ns < round_start) {
        unanswered.push_back(io.id);
      }
    }
    const bool command_ready = unanswered.empty();
    const bool others_ready = !barrier_ || barrier_->poll(round_start);
    if (!command_ready || !others_ready) {
      const std::int64_t now = common::steadyTimeNs();
      std::vector<std::string> waiting_for;
      if (!command_ready) {
        waiting_for.emplace_back("control");
      }
      if (barrier_ && !others_ready) {
        for (std::string& name : barrier_->ledger().lateNames(round_start)) {
          waiting_for.push_back(std::move(name));
        }
      }
      round_.waitingFor(now, std::move(waiting_for));
      if (round_.resendDue(now)) {
        // Every vehicle's depth frame, state, IMU sample and clock of the round (an answer to
        // a repeat is the same answer: the mapper knows a cloud it has by its stamp).
        for (std::size_t i = 0; i < io_.size(); ++i) {
          VehicleIo& io = io_[i];
          if (io.last_depth) {
            depth_.writeFor(io.id, *io.last_depth);
          }
          if (io.last_state && io.last_state->t_ns >= round_start) {
            state_.writeFor(io.id, toMessage(*io.last_state));
          }
          if (io.last_imu && io.last_imu->header().stamp_ns() >= round_start) {
            imu_.writeFor(io.id, *io.last_imu);
          }
          publishClock(i);
        }
        round_.resent(now);
      }
      if (round_.reportDue(now)) {
        std::string late;
        if (!command_ready) {
          late = io_.size() == 1 ? "control (no command for t = " + std::to_string(round_start) + " ns)"
                                 : fmt::format("control of vehicles {} (no command for t = {} ns)",
                                               fmt::join(unanswered, ", "), round_start);
        }
        if (barrier_ && !others_ready) {
          for (const auto& l : barrier_->ledger().late(round_start)) {
            late += (late.empty() ? "" : ", ") + l;
          }
        }
        spdlog::warn("lockstep: at sim time {:.3f} s, still waiting after {:.1f} s for: {}",
                     common::toSeconds(round_start), common::toSeconds(round_.waitedNs(now)), late);
      }
      return;  // woken again by commands or reports
    }
    if (round_.waiting()) {
      round_.inputsIn(common::steadyTimeNs());
    }
    while (!stopping() && fleet_->timeNs() < round_.end()) {
      stepOnce();
    }
    round_.close();
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

void PlantNode::logLockstepWaits() const
{
  // Whom the clock waited for, the longest waits first: what holds a lockstep run back.
  std::vector<std::pair<std::string, runtime::LockstepRound::Wait>> waits(round_.waits().begin(), round_.waits().end());
  std::sort(waits.begin(), waits.end(), [](const auto& a, const auto& b) { return a.second.wall_ns > b.second.wall_ns; });
  std::string each;
  for (const auto& [name, wait] : waits) {
    each += fmt::format("{}{} {:.3f} s in {} rounds", each.empty() ? "" : ", ", name, common::toSeconds(wait.wall_ns),
                        wait.rounds);
  }
  spdlog::info("lockstep: the clock waited in {} rounds, {:.3f} s of wall time in all{}{}", round_.roundsWaited(),
               common::toSeconds(round_.waitedWallNs()), each.empty() ? "" : ": for ", each);
}

void PlantNode::onStop()
{
  for (std::size_t i = 0; i < io_.size(); ++i) {
    const Simulation& sim = fleet_->vehicle(i);
    const std::string who = io_.size() > 1 ? fmt::format("vehicle {} ", io_[i].id) : std::string();
    const auto& c = sim.commands().counters();
    const std::uint64_t collisions = fleet_->collisionCount(i);
    const std::string summary =
        "sim time " + std::to_string(common::toSeconds(sim.timeNs())) + " s, collisions " +
        std::to_string(collisions) + ", commands accepted " + std::to_string(c.accepted) +
        ", clamped " + std::to_string(c.clamped) + ", rejected " +
        std::to_string(c.rejected_invalid + c.rejected_late + c.rejected_old) + ", stale steps " +
        std::to_string(c.stale_steps) + ", failsafe steps " + std::to_string(c.failsafe_steps) +
        ", dropped steps " + std::to_string(dropped_steps_);
    spdlog::info("plant: {}run ended: {}", who, summary);
    if (const auto& battery = sim.battery()) {
      spdlog::info("plant: {}battery {:.1f} % left ({:.2f} of {:.2f} Ah), {:.1f} Wh drawn, {} of {} cells working", who,
                   100.0 * battery->charge(), battery->chargeAh(), battery->config().capacity,
                   battery->energyDrawn() / 3600.0, battery->workingCells(), battery->config().cells);
    }
    const auto& st = sim.state();
    // Full precision, so that runs can be compared bit for bit from their logs.
    spdlog::info("plant: {}final state t {} ns p ({:.17g}, {:.17g}, {:.17g}) q ({:.17g}, {:.17g}, {:.17g}, {:.17g})",
                 who, sim.timeNs(), st.p_W.x(), st.p_W.y(), st.p_W.z(), st.q_WB.w, st.q_WB.x, st.q_WB.y, st.q_WB.z);
    event(i, msg::SIM_EVENT_RUN_ENDED, static_cast<std::int64_t>(collisions), summary);
  }
  if (io_.size() > 1) {
    spdlog::info("plant: the least separation between two vehicles was {:.3f} m", fleet_->minimumSeparation());
  }
  if (config_.mode == PlantNodeConfig::Mode::kLockstep) {
    logLockstepWaits();
  }
  // The run's last word (its final position and collisions) must reach the readers before
  // the participant goes: a reliable sample still unacknowledged at exit is lost.
  if (!events_.waitForAcknowledgments(kFinalEventWait)) {
    spdlog::warn("plant: {}: the run's end was not acknowledged by every reader within {} ms",
                 dds::topics::kSimEvents.info.name, kFinalEventWait.count());
  }
}

runtime::ModuleEntry plantModule() { return runtime::moduleEntry<PlantNode>("plant", plantSchema(), plantConfigFrom); }

}  // namespace quad::plant
