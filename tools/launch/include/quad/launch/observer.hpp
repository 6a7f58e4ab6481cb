// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The launcher's own DDS participant: tells whether topics are live (a writer was
/// discovered), and plays the operator of a mission (gives the goal, which asks the controller
/// to land there) while feeding a MissionTracker with what the stack publishes.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "quad/launch/estimate_score.hpp"
#include "quad/launch/mission.hpp"
#include "quad/dds/participant.hpp"

namespace quad::launch {

/// Why a path status means the goal cannot be reached, in words; empty when it does not.
std::string noPathReason(int status);
/// "HOVER" for CONTROL_HOVER: a ControlMode's name from the IDL, without its prefix.
std::string controlModeName(int mode);
/// Every ControlMode's name, in that form.
std::vector<std::string> controlModeNames();

/// A module's heartbeat, as the launcher follows its modules' lives.
struct ModuleBeat {
  std::string module;      ///< Heartbeat.module_name: the module's kind ("mapping", ...)
  std::int32_t pid = 0;    ///< on its host
  bool running = false;    ///< state MODULE_RUNNING (or DEGRADED: running, working around an error)
  std::int64_t stamp_ns = 0;  ///< wall time on its host
};

class Observer {
public:
  explicit Observer(dds::ParticipantOptions options);
  ~Observer();

  /// The topics of `topics` with no writer discovered yet.
  std::vector<std::string> missingWriters(const std::vector<std::string>& topics) const;

  /// Starts following a mission to `world`'s goal: publishes the goal (latched).
  void startMission(const Mission& mission, const world::World& world, double radius);
  /// Whether every reader of the mission's goal discovered so far has matched its writer and
  /// acknowledged the goal; true without a mission.
  bool goalDelivered();
  /// Takes what arrived, feeds the tracker, sends the land command when it asks.
  void update();
  /// The modules' heartbeats that arrived since the last call.
  std::vector<ModuleBeat> takeHeartbeats();
  /// Null until startMission.
  MissionTracker* mission() { return tracker_.get(); }
  /// The operator's station: while a mission is followed, the launcher is it and sends its
  /// heartbeat (quad/system/operator_heartbeat) every half second of sim time, unless the link is
  /// down (a fault: the controller's link-loss failsafe then acts).
  void setOperatorLink(bool up) { operator_link_ = up; }
  /// Wall time [ns, steady] of the last vehicle state; 0 before the first.
  std::int64_t lastStateNs() const { return last_state_ns_; }
  /// For tools that act on the run through the launcher's participant (quad fault).
  dds::Participant& participant() { return participant_; }
  /// The newest sim time the plant's clock told [ns]; 0 before the first.
  std::int64_t simTimeNs() const;  ///< the newest sim time the plant's clock told
  /// The vehicle's position in the newest state the clock vouches for.
  const Eigen::Vector3d& position() const { return position_; }
  /// The estimator's state against the truth, so far (whatever the stack flies on).
  const EstimateScore& estimateScore() const { return score_; }

private:
  struct Sim;
  struct Endpoints;
  dds::Participant participant_;
  std::unique_ptr<Sim> sim_;
  std::unique_ptr<Endpoints> endpoints_;
  std::unique_ptr<MissionTracker> tracker_;
  std::int64_t last_state_ns_ = 0;
  bool operator_link_ = true;
  std::int64_t next_operator_beat_ns_ = 0;  // sim time the station's next heartbeat is due
  std::int64_t state_ns_ = 0;  // stamp of the newest state taken
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero();
  EstimateScore score_;
};

}  // namespace quad::launch
