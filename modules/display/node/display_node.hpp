// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The display participant: watches the flight and publishes it in Foxglove's display
/// schemas (the quad/display/* topics), so that Foxglove and Lichtblick draw it live or from
/// a recording. It flies nothing: no module reads what it writes.

#include <map>
#include <optional>
#include <string>

#include "quad/display/display_params.hpp"
#include "quad/display/event_log.hpp"
#include "quad/display/occupied_voxels.hpp"
#include "quad/display/packed_cloud.hpp"
#include "quad/display/scene.hpp"
#include "quad/mapping/map_follower.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/state_input.hpp"

namespace quad::display {

/// The frames of the display topics, as viewers show them (and configs/viewer/ names them).
inline constexpr const char* kWorldFrame = "world";
inline constexpr const char* kBodyFrame = "body";          ///< the state the stack flies on
inline constexpr const char* kTrueBodyFrame = "body_true";  ///< the simulator's truth

struct DisplayNodeConfig : DisplayParams {
  runtime::StateSource state_source = runtime::StateSource::kEstimate;
  double state_rate = 50.0;  ///< [Hz] of sim time, at most: the states read (flown on, and the truth); 0: every one
};

const common::ParamTable<DisplayNodeConfig>& displayNodeTable();
common::ParamSchema displayNodeSchema();
DisplayNodeConfig displayConfigFrom(const common::Params& params);

class DisplayNode : public runtime::Node {
public:
  DisplayNode(DisplayNodeConfig config, dds::Participant handle);

protected:
  void onTick(std::int64_t steady_ns) override;

private:
  void takeStates();
  void takeDepth();
  void takeMap();
  /// Whether map messages of `resolution` can be followed (the first sets the map's).
  bool followMap(double resolution, std::string_view topic);
  void takeScene();
  void takePaths();
  void takeTrajectories();
  void takeLogLines();
  void publishTransforms(std::int64_t t_ns);
  void publishTrajectories(std::int64_t t_ns);
  void log(const LogLine& line);

  DisplayNodeConfig config_;
  std::vector<Shape> obstacles_;  // the world's solid shapes: obstacles, then a scan's boxes
  Trace trace_;
  Trace true_trace_;
  EventLog events_;

  runtime::StateInput state_;
  std::optional<runtime::StateInput> truth_;  // when the stack flies on the estimate
  dds::Subscriber<msg::PointCloud> depth_;
  dds::Subscriber<msg::MapUpdate> updates_;
  dds::Subscriber<msg::MapSnapshot> snapshots_;
  dds::Subscriber<msg::Goal> goals_;
  dds::Subscriber<msg::GoalAck> goal_acks_;
  dds::Subscriber<msg::Path> paths_;
  dds::Subscriber<msg::Trajectory> trajectories_;
  dds::Subscriber<msg::ControlStatus> status_;
  dds::Subscriber<msg::CommandAck> command_acks_;
  dds::Subscriber<msg::SimEvent> sim_events_;
  dds::Subscriber<msg::SimEvent> fault_events_;

  dds::Publisher<foxglove::FrameTransforms> transforms_;
  dds::Publisher<foxglove::PosesInFrame> trajectory_;
  dds::Publisher<foxglove::PosesInFrame> true_trajectory_;
  dds::Publisher<foxglove::PosesInFrame> path_;
  dds::Publisher<foxglove::PosesInFrame> plan_;
  dds::Publisher<foxglove::PointCloud> map_;
  dds::Publisher<foxglove::SceneUpdate> scene_;
  dds::Publisher<foxglove::PointCloud> depth_cloud_;
  dds::Publisher<foxglove::Log> log_;

  std::optional<runtime::StateSample> body_;   // the newest state flown on
  std::optional<TracePose> body_true_;     // the newest true state
  std::map<std::string, foxglove::FrameTransform> sensors_;  // body to each depth sensor, by frame
  std::int64_t next_transforms_ns_ = 0;
  std::int64_t next_trajectory_ns_ = 0;
  std::optional<mapping::MapFollower> follower_;  // from the first map message's resolution
  std::optional<OccupiedVoxels> occupied_;
  std::int64_t map_ns_ = 0;  // the newest map message's stamp
  std::int64_t next_map_ns_ = 0;
  bool scene_sent_ = false;
};

/// The display module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry displayModule();

}  // namespace quad::display
