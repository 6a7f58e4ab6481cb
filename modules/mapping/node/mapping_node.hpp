// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The mapping participant: integrates depth clouds into the map, publishes each scan's
/// change set, a snapshot for late joiners and per-scan stats, and takes part in lockstep.

#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/mapping/depth_intake.hpp"
#include "quad/mapping/mapper.hpp"
#include "quad/mapping/pose_history.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/state_input.hpp"
#include "quad/runtime/state_timed.hpp"

namespace quad::mapping {

struct MappingNodeConfig {
  MapperConfig map;
  std::set<std::string> frames;      ///< sensor frames accepted
  double snapshot_period_s = 1.0;    ///< [s] of sim time between snapshots
  std::filesystem::path save_path;   ///< .bt written on shutdown and on COMMAND_SAVE_MAP; empty: never
  /// Resumed from when it exists at the start, written with every snapshot and on shutdown;
  /// empty: none (a mapper started again begins with an empty map).
  std::filesystem::path checkpoint_file;
  runtime::StateSource state_source = runtime::StateSource::kEstimate;  ///< where the body's pose comes from
  /// [ns] of sim time: one state read per period (a cloud between two is placed on the pose
  /// interpolated between them); 0: every state.
  std::int64_t state_period_ns = 0;
};

/// configs/mapping.yaml as written.
struct MappingParams {
  MapperParams mapper;
  std::filesystem::path world_file;                      ///< empty: the map is unbounded
  std::set<std::string> frames{"depth_front"};           ///< sensor frames accepted
  double snapshot_period_s = 1.0;                        ///< [s] of sim time between snapshots
  std::string save_path;                                 ///< .bt file; empty: never saved
  std::string checkpoint_file;                           ///< empty: none
  runtime::StateSource state_source = runtime::StateSource::kEstimate;
  double state_rate = 50.0;  ///< [Hz] of sim time, at most; 0: every state
};

/// Each key with its unit, range and the field it fills; the defaults are MappingParams'.
const common::ParamTable<MappingParams>& mappingTable();
common::ParamSchema mappingSchema();
MappingNodeConfig mappingConfigFrom(const common::Params& params);

class MappingNode : public runtime::Node {
public:
  MappingNode(MappingNodeConfig config, dds::Participant handle);

protected:
  void onWake() override;
  void onEvent(const dds::EndpointEvent& event) override;
  void onStop() override;

private:
  /// Takes the vehicle states into the pose history.
  void takeStates();
  /// Integrates the clouds waiting for the body's pose at their time, in order; one with no
  /// state at its time (dropped, or never coming) is refused.
  void integratePending();
  /// Integrates one cloud, the body at `body_W` (none: refused, `why`).
  void integrate(const msg::PointCloud& cloud, const std::optional<geometry::Pose3>& body_W, const std::string& why);
  void reportLockstep();
  /// The snapshot (and checkpoint) owed by the last cloud integrated, if one is: taken before
  /// the next cloud changes the map, and otherwise once the lockstep report is out, so that
  /// the clock never waits for its walk of the tree. The tree is settled and walked on a
  /// thread of its own (Mapper::imageLater) while the next clouds are integrated.
  void takeOwedSnapshot();
  /// The snapshot whose image is being worked out, published with its checkpoint: once the
  /// image is ready, or with `wait` when it is.
  void finishSnapshot(bool wait);
  void save();
  /// The map's .bt bytes on the latched snapshot topic, stamped `stamp_ns`, as of update `update_seq`.
  void publishSnapshot(std::int64_t stamp_ns, std::uint64_t update_seq, const std::vector<std::uint8_t>& bytes);
  /// The period the states are read at: the config's, or 0 (every one) when the budget is shorter.
  std::int64_t statePeriodNs();
  /// Resumes from the checkpoint file, if there is one (throws naming it when it is bad).
  void resume();
  /// Writes the checkpoint (when there is a file), reserving update numbers up to `floor`;
  /// `tree_data`: the tree's node data when the caller has it (a snapshot's walk gave it).
  void checkpoint(std::int64_t stamp_ns, std::uint64_t floor, const std::vector<std::uint8_t>* tree_data = nullptr);

  MappingNodeConfig config_;
  Mapper mapper_;
  dds::Subscriber<msg::PointCloud> depth_;
  runtime::StateInput state_;
  dds::Subscriber<msg::VehicleCommand> commands_;
  dds::Publisher<msg::MapUpdate> updates_;
  dds::Publisher<msg::MapSnapshot> snapshots_;
  dds::Publisher<msg::MapStats> stats_;
  runtime::LockstepReporter lockstep_;

  PoseHistory poses_;
  std::int64_t states_heard_ns_ = -1;    // the newest state's stamp, an estimate still aligning included
  // Clouds waiting for the state of their time; in real time for up to 0.5 s of sim time.
  runtime::StateTimed<msg::PointCloud> pending_{500'000'000};
  std::uint64_t frames_taken_ = 0;         // depth frames dealt with (integrated, refused or skipped)
  std::uint64_t frames_reported_ = 0;      // lockstep: frames_taken_ when it was last reported
  std::uint64_t update_seq_ = 0;
  std::uint64_t reserved_seq_ = 0;  // numbers below this are in the checkpoint's reservation
  std::int64_t last_stamp_ns_ = 0;  // the newest cloud integrated
  std::int64_t taken_stamp_ns_ = -1;  // the newest cloud dealt with in this run (-1: none)
  std::uint64_t overruns_ = 0;       // updates the lockstep clock reached the due time of first
  std::int64_t next_snapshot_ns_ = 0;
  // A newly matched update reader: snapshots go with every cloud up to match_until_ns_.
  bool match_pending_ = false;
  std::int64_t match_until_ns_ = -1;
  struct OwedSnapshot {
    std::int64_t due_ns;    // its cloud's update's due time: the snapshot's stamp
    std::int64_t stamp_ns;  // its cloud's: the checkpoint's
    bool periodic;          // one of the period's: the map's memory is counted with it
  };
  std::optional<OwedSnapshot> owed_snapshot_;
  struct SnapshotJob {
    std::shared_future<TreeImage> image;
    OwedSnapshot owed;
    std::uint64_t update_seq;    // the last update out when it was taken
    std::uint64_t reserved_seq;  // the reservation then, which its checkpoint keeps
    std::uint64_t frames;        // frames_taken_ then
  };
  std::optional<SnapshotJob> snapshot_job_;  // taken, not yet published
  // A period's snapshot's count of the map's nodes and bytes, for the stats from the scan
  // that makes frames_taken_ reach from_frames on.
  struct Figures {
    std::uint64_t from_frames;
    std::size_t nodes;
    std::size_t bytes;
  };
  static constexpr std::uint64_t kFiguresLagScans = 3;
  std::optional<Figures> figures_;
  std::uint64_t rejected_ = 0;
  std::uint64_t skipped_ = 0;
  DepthIntake intake_;                 // what of a cloud is mapped, or why it is refused
  // MapStats' tree memory and nodes, as of a periodic snapshot (figures_): OctoMap counts the
  // memory by walking the whole tree, which per cloud took a fifth of the mapper's time in the
  // demo, and the tree is only settled for the snapshots.
  std::size_t map_bytes_ = 0;
  std::size_t map_nodes_ = 0;
};

/// The mapping module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry mappingModule();

}  // namespace quad::mapping
