// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Follows a mission from what the stack publishes (vehicle state, controller mode, paths,
/// collisions) and says when it is over and how it went. No DDS: the launcher feeds it.

#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "quad/launch/estimate_score.hpp"
#include "quad/launch/manifest.hpp"
#include "quad/world/world.hpp"

namespace quad::launch {

/// How a mission ended, for the exit status: each kind its own (docs/launch.md).
enum class MissionEnd { kUnfinished, kSuccess, kFailed, kNoPath, kCrashed };
/// "unfinished", "success", "failed", "no_path", "crashed": the summary's `end`.
std::string_view toString(MissionEnd end);

/// What a process of the run cost: the CPU time it took over the run (user and system, all
/// its threads; a restarted module's instances together), that over the run's wall time (the
/// share of one core it kept busy), and the most memory it held resident. Unknown for a module
/// run on another host.
struct ProcessCost {
  std::string name;               ///< the manifest's module name, "record", "discovery", or "launch" itself
  std::optional<double> cpu_s;
  std::optional<double> max_rss_mib;  ///< the most it held resident at once [MiB]
  /// Its threads' waits (common::waits): each a wake-up, by a sample, a lock or a timeout.
  std::optional<std::uint64_t> waits;
};
/// cpu_s over the run's wall time; nothing when either is unknown.
std::optional<double> busyShare(const ProcessCost& p, double wall_s);

struct MissionSummary {
  bool success = false;
  MissionEnd end = MissionEnd::kUnfinished;
  std::string outcome;          ///< "landed at the goal", "timed out 3.2 m from the goal", ...
  std::string failure;          ///< why it failed, in words ("" when it succeeded)
  int collisions = 0;
  std::string state;            ///< what the stack flew on: "estimate" or "truth" (the manifest's ${state})
  double sim_s = 0.0;           ///< sim time when the mission ended
  double wall_s = 0.0;
  /// [s] Wall time from the launcher's start to the first vehicle state: every module started
  /// and, in lockstep, discovered by the plant, whose clock waits for them. Nothing when no
  /// state came.
  std::optional<double> startup_s;
  /// [s] Wall time from the first vehicle state to the last: the flight, without the start-up
  /// and the stop. Nothing when no state came.
  std::optional<double> flight_wall_s;
  double path_length_m = 0.0;   ///< flown, from the vehicle states
  double straight_line_m = 0.0; ///< start to goal
  /// [s] sim time from the mission's start (the controller's first MISSION) to the goal's
  /// tolerance; nothing when the goal was not reached
  std::optional<double> time_to_goal_s;
  /// [m/s] the length flown over that time; nothing when the goal was not reached
  std::optional<double> average_speed_mps;
  double top_speed_mps = 0.0;   ///< [m/s] the most between two vehicle states scored
  /// [s] Sim time from a depth frame to the command that reacts to it: for each trajectory the
  /// controller took for a path during the mission, from the newest depth frame in the map the
  /// path was planned on to the trajectory's first command (Trajectory.depth_stamp_ns). The
  /// median and the most; nothing when no such trajectory came. A fleet's: its slowest vehicle's.
  std::optional<double> depth_to_command_median_s;
  std::optional<double> depth_to_command_max_s;
  std::optional<double> optimum_m; ///< the known-map optimum (quad plan), when the run has a planner
  int paths = 0;                ///< path versions received (the planner's replans that changed the path)
  /// Map updates the lockstep clock reached the due time of before the mapper had them out
  /// (MapStats.overruns, the newest heard); nothing when no mapper's stats came.
  std::optional<std::uint64_t> map_overruns;
  /// Paths the lockstep clock reached the due time of before the planner had them out
  /// (Path.overruns, the newest heard); nothing when no path came.
  std::optional<std::uint64_t> path_overruns;
  double min_clearance_m = 0.0; ///< closest the vehicle's bounding sphere came to an obstacle
  int mode_changes = 0;
  std::vector<std::string> modes;  ///< "t MODE" in order
  double goal_distance_m = 0.0; ///< at the end
  std::vector<ProcessCost> processes;  ///< filled by the launcher once its processes ended
  std::optional<EstimateErrors> estimate;  ///< the estimator against the truth; none without an estimator
  /// A fleet vehicle's summary: its id.
  std::optional<std::uint32_t> vehicle_id;
  /// A fleet's summary: one per vehicle, in the manifest's order; the fields above then stand
  /// for the whole fleet (fleetSummary).
  std::vector<MissionSummary> vehicles;
  /// [m] A fleet's least distance between two vehicles' bounding spheres (negative: they
  /// touched); nothing for one vehicle.
  std::optional<double> min_separation_m;
};

/// The whole fleet's summary from its vehicles': a success when every vehicle's is; collisions,
/// lengths, optima (when every vehicle has one), paths and mode changes summed; the longest sim
/// time and goal distance, the closest approach to an obstacle; the failure names each vehicle
/// that failed, and the end is the first failed vehicle's (a no-path end only when every
/// vehicle that did not succeed ended so).
MissionSummary fleetSummary(std::vector<MissionSummary> vehicles, std::optional<double> min_separation_m,
                            double wall_s);

class MissionTracker {
public:
  /// `radius`: the vehicle's bounding sphere [m]; 0 measures clearance from its centre.
  MissionTracker(Mission mission, const world::World& world, double radius);
  // Each kind of sample comes in order of its stamps, but the kinds may come interleaved in
  // any way (readers taken one after another): every figure of the summary is judged by the
  // samples' stamps, so the same samples give the same summary however they were interleaved.

  /// A vehicle state at sim time t [s].
  void onState(double t, const Eigen::Vector3d& p);
  /// The controller's mode (its name) at sim time t; repeats are ignored. `ended_by`: a
  /// failsafe of the controller's that ends the flight short of the goal, in words ("the
  /// vehicle left the geofence", "the battery ran low"), empty for none; the first one heard is
  /// the failure a landing short of the goal reports.
  void onMode(double t, const std::string& mode, const std::string& ended_by = {});
  /// A path of this version was published at sim time t [s]. `no_path`: the planner said the
  /// goal cannot be reached, and why (in words); empty when it has a path or is merely waiting.
  void onPath(double t, std::uint32_t version, const std::string& no_path = {});
  /// The controller took a trajectory at sim time t [s] for a path planned on a map whose
  /// newest depth frame is from `depth_t` [s].
  void onTrajectory(double t, double depth_t);
  /// The plant reported a collision.
  void onCollision(double t);
  /// The vehicle hit a solid and stopped there (`detail`: what, at what speed): the mission
  /// ends crashed.
  void onCrash(double t, const std::string& detail);
  /// The mapper's count of updates over its budget (MapStats.overruns).
  void onMapStats(std::uint64_t overruns);
  /// The planner's count of paths over its budget (Path.overruns).
  void onPathOverruns(std::uint64_t overruns);

  /// Lines worth printing while the mission flies ("t = 12.3 s: MISSION -> HOVER"), once each.
  std::vector<std::string> takeProgress();

  bool finished() const { return finished_; }
  /// [s] The sim time of the state or mode that ended the mission (finished() only): what
  /// is scored of a run ends there, however late its end is heard.
  double endTime() const { return end_t_; }
  double simTime() const { return t_; }
  MissionSummary summary(double wall_s) const;

private:
  void finish(double t, MissionEnd end, std::string outcome, std::string failure = {});
  /// At the goal: a success unless the vehicle collided on the way.
  void finishAtGoal(double t, const std::string& outcome);

  Mission mission_;
  const world::World& world_;
  double radius_;
  Eigen::Vector3d goal_;
  double t_ = 0.0;
  std::optional<Eigen::Vector3d> last_p_;
  double last_t_ = 0.0;           // of last_p_
  double length_ = 0.0;
  double top_speed_ = 0.0;
  std::optional<double> mission_t_;       // the first MISSION
  double mission_length_ = 0.0;           // length_ at the last state stamped at or before it
  std::deque<std::pair<double, double>> recent_lengths_;  // (t, length_) of the latest states
  std::optional<double> goal_t_;          // within the goal's tolerance
  double goal_length_ = 0.0;              // length_ then
  double min_clearance_;
  std::string mode_;
  std::vector<std::string> modes_;
  std::vector<std::pair<double, std::string>> mode_times_;  // each mode change, in order
  std::uint32_t last_version_ = 0;
  std::vector<double> path_times_;        // the stamp of each new path version
  std::vector<std::pair<double, double>> depth_latencies_;  // (t, [s]) onTrajectory's
  std::optional<std::uint64_t> map_overruns_;
  std::optional<std::uint64_t> path_overruns_;
  int collisions_ = 0;
  bool goal_reached_ = false;
  bool finished_ = false;
  double end_t_ = 0.0;
  MissionEnd end_ = MissionEnd::kUnfinished;
  std::string outcome_;
  std::string failure_;
  std::string no_path_;   // the planner's last word that the goal cannot be reached
  std::string gave_up_;   // the no-path word in force when the controller left for RETURN or LAND
  std::string ended_by_;  // the first flight-ending failsafe the controller reported
  double ended_by_t_ = 0.0;  // and when
  std::vector<std::string> progress_;
  double next_progress_t_ = 10.0;
};

/// Why a mission to this world's goal cannot be flown at all, naming the goal: it lies outside
/// the world's bounds or the geofence, or inside an obstacle or within `radius` [m] of one; or
/// the vehicle starts outside the geofence. Nothing when it can.
std::optional<std::string> goalProblem(const world::World& world, double radius,
                                       const common::Geofence& fence = {});

/// Why a fleet cannot fly in `world` as the manifest places it, one problem per vehicle
/// ("vehicles[1] (id 2): ..."): its goal as goalProblem finds it; its start outside the
/// world's bounds or within its radius of an obstacle; two vehicles whose spheres overlap at
/// their starts. `radii` [m] are the vehicles', in the manifest's order.
std::vector<std::string> fleetProblems(const world::World& world, const std::vector<FleetMember>& vehicles,
                                       const std::vector<double>& radii, const common::Geofence& fence = {});
/// Vehicle `v`'s view of `world`: the same obstacles and bounds, its start and goal.
world::World memberWorld(const world::World& world, const FleetMember& v);

/// The summary as one JSON object (the --summary file).
std::string toJson(const MissionSummary& s);
/// The summary for people, a few lines.
std::string toText(const MissionSummary& s);

}  // namespace quad::launch
