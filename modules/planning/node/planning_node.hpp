// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The planning participant: keeps D* Lite's graph in step with the mapper's change sets
/// (catching up from snapshots), replans from the vehicle's position to the goal, and
/// publishes the shortened path (republished periodically, so followers know it is alive).

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "quad/dds/module_watch.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/mapping/map_follower.hpp"
#include "quad/planning/deconfliction.hpp"
#include "quad/planning/mapper_lapse.hpp"
#include "quad/planning/planning_params.hpp"
#include "quad/planning/replan.hpp"
#include "quad/runtime/due_queue.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/state_input.hpp"

namespace quad::planning {

/// The node's parameters: the planner's (shared with `quad plan`, `state.rate` among them) and
/// where the vehicle state comes from.
struct PlanningNodeConfig : PlanningParams {
  runtime::StateSource state_source = runtime::StateSource::kEstimate;
};

/// configs/planning.yaml as the node reads it: planningTable() and `state.source`.
const common::ParamTable<PlanningNodeConfig>& planningNodeTable();
common::ParamSchema planningNodeSchema();

/// The planning parameters of a config: its world's box and its vehicle's radius loaded from
/// the files it names. Throws common::ConfigError naming the file or key.
PlanningNodeConfig planningConfigFrom(const common::Params& params);

class PlanningNode : public runtime::Node {
public:
  PlanningNode(PlanningNodeConfig config, dds::Participant handle);

protected:
  void onWake() override;

private:
  /// The states that arrived, in order, held until handled (see the .cpp).
  void takeStates();
  /// The map's updates and snapshots that arrived, held until they take effect.
  void takeMapSamples();
  /// The held map samples due by sim time `at_ns` into the map (see the .cpp).
  void applyMapDue(std::int64_t at_ns);
  /// Depth frames whose updates have taken effect by sim time `at_ns` (see the .cpp).
  std::uint64_t framesDueAt(std::int64_t at_ns);
  /// The oldest held state, once the map due by its time is in (see the .cpp): its goals, its
  /// replan. False when it must wait.
  bool handleState(const runtime::StateSample& s);
  /// The sim time up to which every input is handled (see the .cpp).
  std::int64_t handledNs() const;
  /// In lockstep: reports done up to the handled time plus the path's budget, or says why not.
  void reportLockstep();
  void applySnapshot(const msg::MapSnapshot& snapshot);
  void applyUpdate(const msg::MapUpdate& update);
  /// The voxel changes taken since the last replan, into the planner's graph (see the .cpp).
  void applyPending();
  /// In lockstep: an update due by `at_ns` that the mapper sent and never came (see the .cpp)
  /// is declared lost.
  void noticeLostUpdate(std::int64_t at_ns);
  /// A goal taking effect (or refused, and answered).
  void takeGoal(const msg::Goal& goal);
  void replan(std::int64_t t_ns);
  /// The other vehicles' paths that arrived, into the deconfliction's history.
  void takeFleetPaths();
  /// The other vehicles' tubes this one gives way to, into the planner's graph.
  void applyKeepOut(std::int64_t t_ns);
  void publish(std::int64_t t_ns, bool changed);

  PlanningNodeConfig config_;
  DStarLite planner_;
  mapping::MapFollower follower_;  // the mapper's classification, from updates and snapshots
  dds::Subscriber<msg::MapUpdate> updates_;
  dds::Subscriber<msg::MapSnapshot> snapshots_;
  runtime::StateInput state_;
  dds::Subscriber<msg::Goal> goal_;
  dds::Subscriber<msg::Path> fleet_paths_;  // every vehicle's: the others' for deconfliction
  dds::Subscriber<msg::LockstepReport> reports_;  // polled: the mapper's tell a lost update from a late one
  dds::Publisher<msg::Path> path_;
  dds::Publisher<msg::GoalAck> goal_acks_;
  dds::ModuleWatch mapper_;
  runtime::LockstepReporter lockstep_;

  std::deque<runtime::StateSample> held_states_;     // arrived, not yet handled
  runtime::DueQueue<msg::MapSnapshot> held_snapshots_;  // arrived, not yet due: due at its stamp
  // Arrived, not yet due: held by the depth frames each accounts for (MapUpdate.depth_frames),
  // due once the clock's count of the frames due by the time handled reaches them.
  runtime::DueQueue<msg::MapUpdate> held_updates_;
  // Counts held and compared as due times: a count past this (no clock publishes so many) is
  // held as this, and due only in real time.
  static constexpr std::uint64_t kMaxFramesDue = std::uint64_t{1} << 62;
  std::vector<std::pair<VoxelIndex, Occupancy>> pending_;  // voxel changes not yet in the graph
  std::uint64_t frames_applied_ = 0;    // depth clouds the applied updates account for
  std::int64_t depth_stamp_ns_ = -1;     // the newest depth cloud the applied updates hold (-1: none)
  std::uint64_t refused_updates_ = 0;   // MapUpdate payloads refused on receipt, so far
  bool update_lost_ = false;            // one was refused or never came since the last update applied
  std::int64_t mapper_done_ns_ = 0;     // the mapper's newest lockstep report
  std::int64_t mapper_done_wall_ns_ = 0;  // steady time that report first covered the clock (0: not yet)
  bool map_whole_ = true;               // last said in the log
  bool mapper_lost_ = false;            // last said in the log
  // How long, in lockstep, a lapse of its heartbeat lasts before it counts: its liveliness
  // lease, in sim time.
  planning::MapperLapse mapper_lapse_;
  std::int64_t joining_since_ns_ = 0;   // steady time it began waiting for the first snapshot (0: not)
  std::string waiting_for_;             // why the oldest held state waits (for lockstep's log)
  bool goal_changed_ = false;
  runtime::DueQueue<msg::Goal> goals_due_;  // in lockstep: goals taken, not yet due
  std::optional<std::uint32_t> goal_id_;
  /// Answers a goal on quad/planning/goal_ack.
  void answerGoal(std::uint32_t goal_id, bool accepted, const std::string& reason);
  std::optional<Vector3> position_;
  Vector3 velocity_ = Vector3::Zero();  // at position_
  std::int64_t now_ns_ = 0;
  std::int64_t next_replan_ns_ = 0;
  std::int64_t next_publish_ns_ = 0;
  std::uint32_t version_ = 0;
  std::uint64_t overruns_ = 0;  // paths the lockstep clock reached the due time of first
  msg::Path current_;
  /// The newest replan, which current_ holds: a new one is a new version when it differs
  /// (changedPath). Before any, an empty path's: no waypoints, PLAN_OK as the message's default.
  Replan previous_{.result = {.status = PlanStatus::kOk}};
  Deconfliction deconfliction_;
  std::vector<std::uint32_t> giving_way_to_;  // last said in the log
};

/// The planning module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry planningModule();

}  // namespace quad::planning
