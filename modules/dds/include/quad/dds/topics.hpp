// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The topic contracts: every topic of quad, declared once. Nodes, tools, the recorder and
/// the docs read them from here; nothing else spells a topic name.

#include <algorithm>
#include <array>
#include <optional>
#include <string_view>

#include "quad/dds/topic.hpp"

namespace quad::dds::topics {

using msg::ActuatorCommand, msg::BaroAltitude, msg::BatteryState, msg::CommandAck, msg::ControlReference, msg::ControlStatus, msg::EstimatedState, msg::FaultCommand, msg::Goal, msg::GoalAck, msg::Heartbeat,
    msg::Imu, msg::LockstepReport, msg::MagneticField, msg::MapSnapshot, msg::MapStats, msg::MapUpdate, msg::Path,
    msg::PointCloud, msg::PositionFix, msg::Range, msg::SimClock, msg::SimEvent, msg::Trajectory, msg::VehicleCommand,
    msg::VehicleState;
// The display topics carry Foxglove's schemas (foxglove::*), for viewers: docs/recording.md.
using FrameTransforms = foxglove::FrameTransforms;
using DisplayLog = foxglove::Log;
using DisplayCloud = foxglove::PointCloud;
using PosesInFrame = foxglove::PosesInFrame;
using SceneUpdate = foxglove::SceneUpdate;

// clang-format off
inline constexpr auto kSimClock = makeTopic<SimClock>(
    "quad/sim/clock", "clock", 250.0, Owner::kPlant,
    "Simulation time, once per plant step");
inline constexpr auto kSimState = makeTopic<VehicleState>(
    "quad/sim/state", "state", 250.0, Owner::kPlant,
    "Ground-truth vehicle state, for scoring: modules fly on it only with state.source: truth", 0.1);
inline constexpr auto kSimImu = makeTopic<Imu>(
    "quad/sim/imu", "sensor", 250.0, Owner::kPlant,
    "Simulated IMU");
inline constexpr auto kSimPosition = makeTopic<PositionFix>(
    "quad/sim/position", "sensor", 10.0, Owner::kPlant,
    "Absolute position fixes (GNSS or motion capture), stamped when measured");
inline constexpr auto kSimBaro = makeTopic<BaroAltitude>(
    "quad/sim/baro", "sensor", 25.0, Owner::kPlant,
    "Barometric altitude, its offset of the day and drift included");
inline constexpr auto kSimMag = makeTopic<MagneticField>(
    "quad/sim/mag", "sensor", 50.0, Owner::kPlant,
    "Magnetometer: the field in the body frame");
inline constexpr auto kSimRange = makeTopic<Range>(
    "quad/sim/range", "sensor", 20.0, Owner::kPlant,
    "Downward rangefinder: how far below the body the surface beneath lies");
inline constexpr auto kSimRangeUp = makeTopic<Range>(
    "quad/sim/range_up", "sensor", 20.0, Owner::kPlant,
    "Upward rangefinder: how far above the body the ceiling over it lies");
inline constexpr auto kEstimatedState = makeTopic<EstimatedState>(
    "quad/estimation/state", "state", 250.0, Owner::kEstimation,
    "The estimator's vehicle state: pose, velocity, biases, 1-sigma, health", 0.1);
inline constexpr auto kSimBattery = makeTopic<BatteryState>(
    "quad/sim/battery", "scan", 10.0, Owner::kPlant,
    "Flight battery: voltage under load, current, charge left", 0.5);
inline constexpr auto kSimDepth = makeTopic<PointCloud>(
    "quad/sim/depth", "scan", 10.0, Owner::kPlant,
    "Depth sensor point cloud with the sensor's pose on the body");
inline constexpr auto kSimEvents = makeTopic<SimEvent>(
    "quad/sim/events", "events", 0.0, Owner::kPlant,
    "Collisions, ground contact, faults applied");
inline constexpr auto kLockstep = makeTopic<LockstepReport>(
    "quad/sim/lockstep", "lockstep", 250.0, Owner::kEveryModule,
    "Lockstep participants' 'done up to sim time t' reports");
inline constexpr auto kMapUpdate = makeTopic<MapUpdate>(
    "quad/mapping/update", "changes", 10.0, Owner::kMapping,
    "Voxels whose classification changed, per scan");
inline constexpr auto kMapSnapshot = makeTopic<MapSnapshot>(
    "quad/mapping/octomap", "latched", 1.0, Owner::kMapping,
    "The whole map as OctoMap binary bytes, for late joiners");
inline constexpr auto kMapStats = makeTopic<MapStats>(
    "quad/mapping/stats", "sensor", 10.0, Owner::kMapping,
    "Per scan: insert time, points, changed voxels, map size");
inline constexpr auto kGoal = makeTopic<Goal>(
    "quad/planning/goal", "latched", 0.0, Owner::kOperator,
    "Where the vehicle should go");
inline constexpr auto kGoalAck = makeTopic<GoalAck>(
    "quad/planning/goal_ack", "command", 0.0, Owner::kPlanning,
    "The planner's answer to each goal: taken, or refused and why");
inline constexpr auto kPath = makeTopic<Path>(
    "quad/planning/path", "latched", 0.0, Owner::kPlanning,
    "Planned path, per replan, republished unchanged at least every half deadline", 1.0);
inline constexpr auto kActuators = makeTopic<ActuatorCommand>(
    "quad/control/actuators", "actuators", 250.0, Owner::kControl,
    "Rotor speed and camera gimbal commands");
inline constexpr auto kControlStatus = makeTopic<ControlStatus>(
    "quad/control/status", "latched", 20.0, Owner::kControl,
    "Controller mode, failsafe reason, tracking errors");
inline constexpr auto kCommandAck = makeTopic<CommandAck>(
    "quad/control/command_ack", "command", 0.0, Owner::kControl,
    "The controller's answer to each operator command: taken or refused, and why");
inline constexpr auto kControlReference = makeTopic<ControlReference>(
    "quad/control/reference", "sensor", 250.0, Owner::kControl,
    "The reference the controller tracks, each tick");
inline constexpr auto kTrajectory = makeTopic<Trajectory>(
    "quad/control/trajectory", "latched", 0.0, Owner::kControl,
    "The trajectory the controller flies, whole each time it takes one (a replan, a stop, a hold)");
inline constexpr auto kHeartbeat = makeTopic<Heartbeat>(
    "quad/system/heartbeat", "heartbeat", 2.0, Owner::kEveryModule,
    "Every module's sign of life");
inline constexpr auto kOperatorHeartbeat = makeTopic<Heartbeat>(
    "quad/system/operator_heartbeat", "heartbeat", 2.0, Owner::kOperator,
    "The operator's station's sign of life (the link): silent too long, the controller's failsafe acts");
inline constexpr auto kVehicleCommand = makeTopic<VehicleCommand>(
    "quad/system/command", "command", 0.0, Owner::kOperator,
    "Arm, takeoff, mission, hold, land");
inline constexpr auto kFault = makeTopic<FaultCommand>(
    "quad/system/fault", "command", 0.0, Owner::kFaultTool,
    "Faults for modules to apply");
inline constexpr auto kFaultEvents = makeTopic<SimEvent>(
    "quad/system/fault_events", "events", 0.0, Owner::kFaultTool,
    "Faults applied outside the plant, when they took effect: by the fault tool (processes, "
    "inputs) or a module's datagram fault layer");
inline constexpr auto kDisplayTransforms = makeTopic<FrameTransforms>(
    "quad/display/transforms", "display", 30.0, Owner::kDisplay,
    "Frames for viewers: world to body (the state the stack flies on), to body_true (the "
    "simulator's truth) and body to each depth sensor");
inline constexpr auto kDisplayTrajectory = makeTopic<PosesInFrame>(
    "quad/display/trajectory", "display_latched", 2.0, Owner::kDisplay,
    "The trajectory flown as the stack knows it, in the world frame, whole each time");
inline constexpr auto kDisplayTrueTrajectory = makeTopic<PosesInFrame>(
    "quad/display/true_trajectory", "display_latched", 2.0, Owner::kDisplay,
    "The trajectory flown, from the simulator's truth, in the world frame, whole each time");
inline constexpr auto kDisplayPath = makeTopic<PosesInFrame>(
    "quad/display/path", "display_latched", 0.0, Owner::kDisplay,
    "The planner's current path, in the world frame, per replan");
inline constexpr auto kDisplayPlan = makeTopic<PosesInFrame>(
    "quad/display/plan", "display_latched", 0.0, Owner::kDisplay,
    "The trajectory the controller flies, poses a tenth of a second apart, in the world frame, whole at each new one");
inline constexpr auto kDisplayMap = makeTopic<DisplayCloud>(
    "quad/display/map", "display_latched", 1.0, Owner::kDisplay,
    "The map's occupied voxels as points at their centres, in the world frame, whole when they changed");
inline constexpr auto kDisplayScene = makeTopic<SceneUpdate>(
    "quad/display/scene", "display_latched", 0.0, Owner::kDisplay,
    "The world's obstacles and the goal, whole at each change");
inline constexpr auto kDisplayDepth = makeTopic<DisplayCloud>(
    "quad/display/depth", "display", 10.0, Owner::kDisplay,
    "Each depth scan's hits, in its sensor's frame");
inline constexpr auto kDisplayLog = makeTopic<DisplayLog>(
    "quad/display/log", "events", 0.0, Owner::kDisplay,
    "The flight's events as log lines: modes, failsafes, plans refused, faults, collisions");
// clang-format on

/// How far a true vehicle state may be stamped past the newest sim clock a reader took: the
/// plant sends both each step on separate topics. A state further ahead is a bad input (taken,
/// it would make every true state after it look out of order).
inline constexpr std::int64_t kStateAheadOfClockNs = 500'000'000;

/// In lockstep, an operator's goal or command (quad/planning/goal, quad/system/command) stamped
/// t takes effect with the first vehicle state at or after t plus this: an operator's station
/// waits for no round, and a fixed delay after its stamp, not its arrival, makes the round it
/// lands in the same in every run.
inline constexpr std::int64_t kOperatorInputDelayNs = 100'000'000;

/// When such an input stamped `stamp_ns` and taken at the clock's `clock_ns` takes effect: the
/// delay after its stamp; after the clock's time for one stamped further ahead of it than a
/// state may be (kStateAheadOfClockNs), which would otherwise wait for ever.
constexpr std::int64_t operatorInputDueNs(std::int64_t stamp_ns, std::int64_t clock_ns)
{
  const std::int64_t from = stamp_ns < 0 ? 0 : stamp_ns > clock_ns + kStateAheadOfClockNs ? clock_ns : stamp_ns;
  return from + kOperatorInputDelayNs;
}

/// In lockstep, the mapper's output for a depth frame stamped t (its quad/mapping/update, and
/// the stats and snapshot of that scan) is due at t plus this, and stamped with that time: what
/// an onboard mapper would take. The clock runs on while the mapper works and waits at the due
/// time for an output not yet out (an overrun, which the mapper counts); the planner applies
/// each update when the clock reaches its due time, so its replans see the same map in every
/// run. In real time the mapper takes what it takes, and the planner applies updates as they
/// come.
inline constexpr std::int64_t kMapUpdateBudgetNs = 50'000'000;

/// In lockstep, the planner's path from the vehicle state of time t (the replan on that state,
/// and the map updates due by t) is due at t plus this, and stamped with that time: what an
/// onboard planner would take. The clock runs on while the planner works and waits at the
/// due time for a path not yet out (an overrun, which the planner counts in Path.overruns);
/// the controller flies a path from the first state after its stamp. 0: a path takes effect
/// with the state after the one it was planned on, and the clock waits for the planner every
/// round.
inline constexpr std::int64_t kPathBudgetNs = 100'000'000;

/// Every contract, for tools that iterate over topics.
inline constexpr std::array kAll{
    kSimClock.info, kSimState.info, kSimImu.info, kSimPosition.info, kSimBaro.info, kSimMag.info, kSimRange.info,
    kSimRangeUp.info, kEstimatedState.info, kSimBattery.info, kSimDepth.info, kSimEvents.info, kLockstep.info,
    kMapUpdate.info, kMapSnapshot.info, kMapStats.info, kGoal.info, kGoalAck.info, kPath.info, kActuators.info,
    kControlStatus.info, kCommandAck.info, kControlReference.info, kTrajectory.info, kHeartbeat.info,
    kOperatorHeartbeat.info, kVehicleCommand.info, kFault.info, kFaultEvents.info, kDisplayTransforms.info, kDisplayTrajectory.info,
    kDisplayTrueTrajectory.info, kDisplayPath.info, kDisplayPlan.info, kDisplayMap.info, kDisplayScene.info,
    kDisplayDepth.info, kDisplayLog.info};

/// Topics whose samples come on wall-clock time (liveliness, what the display draws at its
/// tick), in the order participants finish (lockstep's reports) or also when a reader matches
/// (the map's snapshots, sent for every cloud for a while to a reader that joined): two
/// lockstep runs of one seed need not agree on them.
inline constexpr std::array kWallPaced{
    kLockstep.info.name, kMapSnapshot.info.name, kHeartbeat.info.name, kOperatorHeartbeat.info.name, kDisplayTransforms.info.name, kDisplayTrajectory.info.name,
    kDisplayTrueTrajectory.info.name, kDisplayPath.info.name, kDisplayPlan.info.name, kDisplayMap.info.name,
    kDisplayScene.info.name, kDisplayDepth.info.name, kDisplayLog.info.name};

/// Whether `topic` is paced by sim time (not in kWallPaced): what two lockstep runs agree on.
constexpr bool isSimPaced(std::string_view topic)
{
  return std::find(kWallPaced.begin(), kWallPaced.end(), topic) == kWallPaced.end();
}

/// Members that hold wall-clock or measured compute times ("<scoped struct>.<member>"), the
/// writer's sample number, which counts the resends of a participant waiting in wall time for
/// a reader, and the mapper's and the planner's overruns, which count where their compute
/// time outlasted the clock's: in two lockstep runs of one seed every other member of every
/// sim-paced topic agrees.
inline constexpr std::array<std::string_view, 6> kWallClockFields{
    "quad::msg::Header.publish_ns", "quad::msg::Header.seq", "quad::msg::Path.replan_time_s",
    "quad::msg::Path.overruns", "quad::msg::MapStats.insert_time_s", "quad::msg::MapStats.overruns"};

/// The contract of a topic name, if quad declares one.
std::optional<TopicInfo> find(std::string_view name);

}  // namespace quad::dds::topics
