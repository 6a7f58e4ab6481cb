// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The launcher's own DDS participant: tells whether topics are live (a writer was
/// discovered), and plays the operator of a mission (gives the goal, which asks the controller
/// to land there) while feeding a MissionTracker with what the stack publishes.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/launch/estimate_score.hpp"
#include "quad/launch/mission.hpp"

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

/// One vehicle whose mission the launcher follows: its id, the world as it sees it (its start
/// and goal), its bounding sphere's radius [m].
struct MissionVehicle {
  std::uint32_t id = 0;
  world::World world;
  double radius = 0.0;
};

class Observer {
public:
  /// Follows the vehicles `vehicles` (their states, estimates and clock samples; the
  /// participant's own vehicle when empty): one, or a fleet's. `state_period_ns` > 0: of
  /// the true and estimated states, the first of each such period of sim time only (the
  /// flight is scored on them), the rest never sent to it.
  explicit Observer(dds::ParticipantOptions options, std::vector<std::uint32_t> vehicles = {},
                    std::int64_t state_period_ns = 0);
  ~Observer();

  /// The topics of `topics` with no writer discovered yet.
  std::vector<std::string> missingWriters(const std::vector<std::string>& topics) const;

  /// Starts following a mission for each of `vehicles` (ids among the followed ones) to its
  /// world's goal: publishes each vehicle's goal (latched).
  void startMission(const Mission& mission, std::vector<MissionVehicle> vehicles);
  /// Whether every reader of the mission's goal discovered so far has matched its writer and
  /// acknowledged the goal; true without a mission.
  bool goalDelivered();
  /// In a lockstep run whose plant counts this observer among its participants
  /// (QUAD_LOCKSTEP_OBSERVER), holds the first round as the run's recorder does: update()
  /// reports this participant done for good (runtime::kObserverParticipant) for each vehicle once
  /// it reads the plant's clock and states and the states of the run's `estimators`, so
  /// that the scores take in every one from sim time 0. Best-effort states a reader has not
  /// matched yet are lost to it: without the hold a machine slow to discover left the
  /// summary without the first half second of a flight.
  void holdStart(std::size_t estimators);
  /// The first round is held (holdStart) and not yet released for every vehicle: the whole
  /// run waits on this observer, which should look again soon.
  bool holdingStart() const;
  /// Takes what arrived, feeds the trackers, sends the land command when it asks.
  void update();
  /// The modules' heartbeats that arrived since the last call.
  std::vector<ModuleBeat> takeHeartbeats();
  /// The vehicles followed, in the order given.
  std::size_t vehicleCount() const;
  std::uint32_t vehicleId(std::size_t i) const;
  /// Vehicle i's mission; null until startMission.
  MissionTracker* mission(std::size_t i = 0);
  /// Every vehicle's mission is over (false without a mission).
  bool missionsFinished() const;
  /// The operator's station: while a mission is followed, the launcher is it and sends its
  /// heartbeat (quad/system/operator_heartbeat) for each vehicle every half second of sim
  /// time, unless the link is down (a fault: the controller's link-loss failsafe then acts).
  void setOperatorLink(bool up) { operator_link_ = up; }
  /// Wall time [ns, steady] of the newest vehicle state of any vehicle; 0 before the first.
  std::int64_t lastStateNs() const { return last_state_ns_; }
  /// Wall time [ns, steady] of the first vehicle state; 0 before it.
  std::int64_t firstStateNs() const { return first_state_ns_; }
  /// For tools that act on the run through the launcher's participant (quad fault).
  dds::Participant& participant() { return participant_; }
  /// The newest sim time the plant's clock told [ns]; 0 before the first.
  std::int64_t simTimeNs() const;
  /// Vehicle i's position in the newest state the clock vouches for.
  const Eigen::Vector3d& position(std::size_t i = 0) const;
  /// Vehicle i's estimator against the truth, so far (whatever the stack flies on).
  const EstimateScore& estimateScore(std::size_t i = 0) const;
  /// [m] The least distance between two vehicles' bounding spheres in states of one stamp, once
  /// the mission started (negative: they overlapped); nothing with fewer than two vehicles.
  std::optional<double> minimumSeparation() const;

private:
  struct Sim;
  struct Endpoints;
  struct Track;
  struct StartHold;
  /// Releases the held start once the readers it waits for have matched.
  void releaseStart();
  /// The followed vehicle of that id; null for another.
  Track* track(std::uint32_t id);
  void onState(Track& v, std::int64_t stamp_ns, const Eigen::Vector3d& p, const geometry::Quaternion& q,
               const Eigen::Vector3d& v_W);

  dds::Participant participant_;
  std::vector<std::uint32_t> ids_;
  std::vector<Track> tracks_;
  std::unique_ptr<Sim> sim_;
  std::unique_ptr<Endpoints> endpoints_;
  std::unique_ptr<StartHold> start_hold_;
  std::int64_t first_state_ns_ = 0;
  std::int64_t last_state_ns_ = 0;
  bool operator_link_ = true;
  std::int64_t next_operator_beat_ns_ = 0;  // sim time the station's next heartbeat is due
  std::optional<double> min_separation_;
};

}  // namespace quad::launch
