// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The plant participant: owns the simulation of every vehicle (a Fleet; one vehicle without a
/// fleet file), publishes each one's clock, state, IMU, depth and events under its id, takes
/// each one's rotor commands and faults, and paces sim time (real time, or lockstep).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plant_config.hpp"
#include "quad/dds/fleet_publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/plant/fleet.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/lockstep_round.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"

namespace quad::plant {

class PlantNode : public runtime::Node {
public:
  /// Loads vehicle(s), world and fault schedule(s); throws common::ConfigError naming the file.
  PlantNode(PlantNodeConfig config, dds::Participant handle);

  /// The first vehicle (the only one without a fleet file).
  const Simulation& simulation() const { return fleet_->vehicle(0); }
  const Fleet& fleet() const { return *fleet_; }

protected:
  void onStart() override;
  void onWake() override;
  void onTick(std::int64_t steady_ns) override;
  void onStop() override;

private:
  /// What the node keeps of one vehicle between steps; its samples carry its id.
  struct VehicleIo {
    std::uint32_t id = 0;
    std::int64_t latest_command_stamp_ns = -1;
    std::uint64_t depth_frames = 0;              // depth frames published so far
    std::int64_t state_due_ns = -1;              // the newest time a state was due (a clock sample went out)
    std::optional<msg::PointCloud> last_depth;   // lockstep: resent with the state while a round waits
    std::optional<StateSample> last_state;       // last state published
    std::optional<msg::Imu> last_imu;            // last IMU sample published: on an estimate, resent while a round waits
  };

  void takeInputs();
  void takeCommand(std::size_t vehicle, const msg::ActuatorCommand& cmd);
  void takeFault(std::size_t vehicle, const msg::FaultCommand& fault);
  void publish(std::size_t vehicle, const StepOutputs& out);
  void publishClock(std::size_t vehicle);
  /// The time of the newest input a vehicle's controller answers (the state, or the IMU sample
  /// the estimate follows); -1 before the first.
  std::int64_t answeredInputNs(const VehicleIo& io) const;
  void stepOnce();
  void runRealTime(std::int64_t steady_ns);
  void runLockstep();
  /// Whom the lockstep clock waited for over the run, and how long, into the log.
  void logLockstepWaits() const;
  void event(std::size_t vehicle, msg::SimEventKind kind, std::int64_t subject, const std::string& detail);

  PlantNodeConfig config_;
  std::unique_ptr<Fleet> fleet_;
  std::vector<VehicleIo> io_;  // one per vehicle, in the fleet's order
  dds::FleetPublisher<msg::SimClock> clock_;
  dds::FleetPublisher<msg::VehicleState> state_;
  dds::FleetPublisher<msg::Imu> imu_;
  dds::FleetPublisher<msg::PositionFix> position_;
  dds::FleetPublisher<msg::BaroAltitude> baro_;
  dds::FleetPublisher<msg::MagneticField> mag_;
  dds::FleetPublisher<msg::Range> range_;
  dds::FleetPublisher<msg::Range> range_up_;
  dds::FleetPublisher<msg::BatteryState> battery_;
  dds::FleetPublisher<msg::PointCloud> depth_;
  dds::FleetPublisher<msg::SimEvent> events_;
  dds::Subscriber<msg::ActuatorCommand> actuators_;
  dds::Subscriber<msg::FaultCommand> faults_;
  std::unique_ptr<runtime::LockstepBarrier> barrier_;

  std::int64_t wall_start_ns_ = 0;
  runtime::LockstepRound round_;          // lockstep: the round open, and the wait for it
  std::uint64_t dropped_steps_ = 0;        // real time: steps skipped when far behind
};

/// The plant module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry plantModule();

}  // namespace quad::plant
