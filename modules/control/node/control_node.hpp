// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The control participant: answers every vehicle state with rotor commands stamped with that
/// state's time (so the plant's lockstep pairs them), publishes its status and reference, and
/// takes paths, goals and operator commands.

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "control_config.hpp"
#include "quad/control/autostart.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/runtime/due_queue.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/state_input.hpp"

namespace quad::control {

class ControlNode : public runtime::Node {
public:
  ControlNode(ControlNodeConfig config, dds::Participant handle);

protected:
  void onWake() override;
  void onTick(std::int64_t steady_ns) override;
  /// In real time, a DDS deadline event on the state or the path reaches the failsafe at once.
  void onEvent(const dds::EndpointEvent& event) override;

private:
  void takeInputs();
  /// In lockstep, the paths, goals and commands taken that are due at `stamp_ns` (see the .cpp).
  void applyDueInputs(std::int64_t stamp_ns);
  void applyGoal(const msg::Goal& goal);
  void applyPath(const msg::Path& path, double t);
  void control(double t, std::int64_t stamp_ns);
  /// A command when states stopped coming, on the clock's time (lockstep) or the IMU's.
  void controlWithoutState();
  /// In real time, no state and no IMU sample for more than `after_s` [s] of the plant's
  /// clock: a command at the clock's time (nothing while the clock stands still too).
  void controlSilentPlant(double after_s);
  void publishStatus(const FlightOutput& out, std::int64_t stamp_ns);

  ControlNodeConfig config_;
  FlightController fc_;
  Autostart autostart_;  // config autostart: arms, then takes off, until the vehicle is in the air
  runtime::StateInput state_;
  dds::Subscriber<msg::Path> path_;
  dds::Subscriber<msg::Goal> goal_;
  dds::Subscriber<msg::VehicleCommand> command_;
  dds::Subscriber<msg::Imu> imu_;
  dds::Subscriber<msg::BatteryState> battery_;
  dds::Subscriber<msg::Range> range_;
  dds::Subscriber<msg::Range> range_up_;
  dds::Subscriber<msg::Heartbeat> operator_;
  dds::Publisher<msg::ActuatorCommand> actuators_;
  dds::Publisher<msg::ControlStatus> status_;
  dds::Publisher<msg::ControlReference> reference_;
  dds::Publisher<msg::Trajectory> trajectory_;
  dds::Publisher<msg::CommandAck> acks_;

  /// Operator commands taken and not yet applied: one a tick, each answered; in lockstep due
  /// the contract's delay after its stamp.
  struct QueuedCommand {
    std::uint32_t id;
    msg::CommandKind kind;
    Command command;
    double takeoff_altitude;
  };
  runtime::DueQueue<QueuedCommand> commands_;
  std::optional<QueuedCommand> applying_;  // fed to the controller, answered by its next update
  /// Answers `command` on quad/control/command_ack.
  void acknowledge(const QueuedCommand& command, const CommandAnswer& answer, Mode mode, std::int64_t stamp_ns);

  /// In lockstep, paths and goals taken but not yet due.
  runtime::DueQueue<msg::Path> paths_due_;
  runtime::DueQueue<msg::Goal> goals_due_;
  /// In lockstep, IMU, battery and rangefinder samples not yet used: a state stamped t is
  /// answered with those stamped before t only, whether the plant's samples of t came before
  /// the state or after it (they come on other writers than the state's), so that runs repeat.
  runtime::DueQueue<msg::Imu> imu_due_;
  runtime::DueQueue<msg::BatteryState> battery_due_;
  runtime::DueQueue<msg::Range> range_due_;
  runtime::DueQueue<msg::Range> range_up_due_;
  void applyImu(const msg::Imu& m);
  void applyBattery(const msg::BatteryState& b);
  void applyRange(const msg::Range& r);
  void applyRangeUp(const msg::Range& r);
  /// Counts and reports a range sample the controller rejected.
  void checkRange(const msg::Range& r, std::string_view topic, bool accepted);
  void applySensorsBefore(std::int64_t stamp_ns);
  std::int64_t answered_ns_ = -1;          // in lockstep, the stamp of the last command sent
  msg::ActuatorCommand answer_;            // that command, sent again for a state sent again
  std::optional<runtime::StateSample> answered_state_;  // the state it answered (none: the clock's time)
  std::int64_t imu_ns_ = 0;                // the newest IMU sample's sim time
  std::int64_t last_stateless_ns_ = 0;     // the sim time last commanded without a state
  double latest_t_ = -1.0;                 // sim time of the newest state [s]
  std::int64_t latest_wall_ns_ = 0;        // steady time it arrived
  std::int64_t path_wall_ns_ = 0;          // steady time the newest path arrived
  double path_t_ = -1.0;                   // sim time it arrived at [s]
  /// Path.depth_stamp_ns of the recent path versions, each as last applied (a version sent
  /// again with more of it known free is taken again): the trajectory taken for one carries it.
  std::map<std::uint32_t, std::int64_t> path_depth_ns_;
  double next_status_t_ = 0.0;
  FlightOutput last_;
  std::uint64_t refused_ = 0;                        // paths the follower refused so far
  std::optional<std::uint32_t> refused_version_;     // the last path version a refusal was said of
};

/// The control module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry controlModule();

}  // namespace quad::control
