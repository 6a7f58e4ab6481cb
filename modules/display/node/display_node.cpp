// SPDX-License-Identifier: BSD-3-Clause
#include "display_node.hpp"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

#include "quad/common/layout.hpp"
#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/trajectory_messages.hpp"
#include "quad/display/plan.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/mapping/mapper.hpp"
#include "quad/world/world_file.hpp"

namespace quad::display {

namespace {

/// Shapes per scene entity: within every primitive list's bound (foxglove/SceneEntity.idl).
constexpr std::size_t kShapesPerEntity = 4096;
constexpr std::size_t kEntitiesPerScene = 32;  // foxglove/SceneUpdate.idl
/// [ns] of wall time between drains of the readers: a viewer's refresh rate (50 Hz).
constexpr std::int64_t kTickPeriodNs = 20'000'000;
/// [s] between the poses the plan is drawn with.
constexpr double kPlanPeriodS = 0.1;

foxglove::Time toTime(std::int64_t t_ns)
{
  const std::int64_t t = std::max<std::int64_t>(t_ns, 0);
  foxglove::Time time;
  time.sec(static_cast<std::uint32_t>(t / common::kNanosecondsPerSecond));
  time.nsec(static_cast<std::uint32_t>(t % common::kNanosecondsPerSecond));
  return time;
}

foxglove::Vector3 toVector3(const Vector3& v)
{
  foxglove::Vector3 out;
  out.x(v.x());
  out.y(v.y());
  out.z(v.z());
  return out;
}

foxglove::Quaternion toQuaternion(const Quaternion& q)
{
  foxglove::Quaternion out;
  out.x(q.x);
  out.y(q.y);
  out.z(q.z);
  out.w(q.w);
  return out;
}

foxglove::Pose toPose(const Vector3& p, const Quaternion& q)
{
  foxglove::Pose pose;
  pose.position(toVector3(p));
  pose.orientation(toQuaternion(q));
  return pose;
}

foxglove::Color toColor(const Colour& c)
{
  foxglove::Color out;
  out.r(c.r);
  out.g(c.g);
  out.b(c.b);
  out.a(c.a);
  return out;
}

foxglove::FrameTransform transform(std::int64_t t_ns, const char* parent, const std::string& child,
                                   const Vector3& p, const Quaternion& q)
{
  foxglove::FrameTransform tf;
  tf.timestamp(toTime(t_ns));
  tf.parent_frame_id(parent);
  tf.child_frame_id(child);
  tf.translation(toVector3(p));
  tf.rotation(toQuaternion(q));
  return tf;
}

foxglove::PointCloud toCloud(std::int64_t t_ns, const std::string& frame, const PackedCloud& packed)
{
  foxglove::PointCloud cloud;
  cloud.timestamp(toTime(t_ns));
  cloud.frame_id(frame);
  cloud.pose(toPose(Vector3::Zero(), Quaternion::identity()));
  cloud.point_stride(PackedCloud::kStride);
  for (const auto& f : packed.fields) {
    foxglove::PackedElementField field;
    field.name(f.name);
    field.offset(f.offset);
    field.type(f.type == PackedField::Type::kFloat32 ? foxglove::FLOAT32 : foxglove::UINT8);
    cloud.fields().push_back(field);
  }
  cloud.data(packed.data);
  return cloud;
}

void addShape(foxglove::SceneEntity& entity, const Shape& s)
{
  const foxglove::Pose pose = toPose(s.centre_W, s.q_WS);
  switch (s.kind) {
    case Shape::Kind::kBox: {
      foxglove::CubePrimitive cube;
      cube.pose(pose);
      cube.size(toVector3(s.size));
      cube.color(toColor(s.colour));
      entity.cubes().push_back(cube);
      break;
    }
    case Shape::Kind::kCylinder: {
      foxglove::CylinderPrimitive cylinder;
      cylinder.pose(pose);
      cylinder.size(toVector3(s.size));
      cylinder.bottom_scale(1.0);
      cylinder.top_scale(1.0);
      cylinder.color(toColor(s.colour));
      entity.cylinders().push_back(cylinder);
      break;
    }
    case Shape::Kind::kSphere: {
      foxglove::SpherePrimitive sphere;
      sphere.pose(pose);
      sphere.size(toVector3(s.size));
      sphere.color(toColor(s.colour));
      entity.spheres().push_back(sphere);
      break;
    }
  }
}

foxglove::SceneEntity entity(std::int64_t t_ns, const std::string& id)
{
  foxglove::SceneEntity e;
  e.timestamp(toTime(t_ns));
  e.frame_id(kWorldFrame);
  e.id(id);
  return e;
}

std::string enumName(std::string_view type, std::int64_t value)
{
  return introspection::quadSchema().enumeratorName(type, value);
}

}  // namespace

const common::ParamTable<DisplayNodeConfig>& displayNodeTable()
{
  using N = DisplayNodeConfig;
  static const common::ParamTable<N> table = [] {
    common::ParamTable<N> t;
    t.include(displayTable(), [](N& n) -> DisplayParams& { return n; });
    runtime::declareStateSource(t, [](N& n) -> runtime::StateSource& { return n.state_source; },
                                "; the one drawn as the body frame");
    runtime::declareStateRate(t, [](N& n) -> double& { return n.state_rate; }, " (the truth's too)");
    return t;
  }();
  return table;
}

common::ParamSchema displayNodeSchema() { return displayNodeTable().schema(); }

DisplayNodeConfig displayConfigFrom(const common::Params& params)
{
  return displayNodeTable().read(params, common::configDir());
}

DisplayNode::DisplayNode(DisplayNodeConfig config, dds::Participant handle)
    : Node("display", std::move(handle)),
      config_(std::move(config)),
      trace_(config_.trace),
      true_trace_(config_.trace),
      state_(participant(), config_.state_source, nullptr, 0, runtime::statePeriodNs(config_.state_rate)),
      depth_(participant(), dds::topics::kSimDepth, nullptr),
      updates_(participant(), dds::topics::kMapUpdate, nullptr),
      snapshots_(participant(), dds::topics::kMapSnapshot, nullptr),
      goals_(participant(), dds::topics::kGoal, nullptr),
      goal_acks_(participant(), dds::topics::kGoalAck, nullptr),
      paths_(participant(), dds::topics::kPath, nullptr),
      trajectories_(participant(), dds::topics::kTrajectory, nullptr),
      status_(participant(), dds::topics::kControlStatus, nullptr),
      command_acks_(participant(), dds::topics::kCommandAck, nullptr),
      sim_events_(participant(), dds::topics::kSimEvents, nullptr),
      fault_events_(participant(), dds::topics::kFaultEvents, nullptr),
      transforms_(participant(), dds::topics::kDisplayTransforms),
      trajectory_(participant(), dds::topics::kDisplayTrajectory),
      true_trajectory_(participant(), dds::topics::kDisplayTrueTrajectory),
      path_(participant(), dds::topics::kDisplayPath),
      plan_(participant(), dds::topics::kDisplayPlan),
      map_(participant(), dds::topics::kDisplayMap),
      scene_(participant(), dds::topics::kDisplayScene),
      depth_cloud_(participant(), dds::topics::kDisplayDepth),
      log_(participant(), dds::topics::kDisplayLog)
{
  if (config_.state_source == runtime::StateSource::kEstimate) {
    truth_.emplace(participant(), runtime::StateSource::kTruth, nullptr, 0, runtime::statePeriodNs(config_.state_rate));
  }
  if (!config_.world_file.empty()) {
    obstacles_ = worldShapes(world::loadWorld(config_.world_file));  // a scan's voxels as boxes too
  }
  if (obstacles_.size() > kShapesPerEntity * (kEntitiesPerScene - 1)) {
    spdlog::warn("display: {} solid shapes (obstacles and a scan's boxes); the scene draws the first {}", obstacles_.size(),
                 kShapesPerEntity * (kEntitiesPerScene - 1));
    obstacles_.resize(kShapesPerEntity * (kEntitiesPerScene - 1));
  }
  // A viewer's refresh, not each sample: the readers are drained on a wall-clock tick.
  setTickPeriod(kTickPeriodNs);
  spdlog::info("display: body frame from {}, {} solid shapes drawn", state_.topic().name, obstacles_.size());
}

void DisplayNode::onTick(std::int64_t /*steady_ns*/)
{
  takeStates();
  takeDepth();
  takeMap();
  takeScene();
  takePaths();
  takeTrajectories();
  takeLogLines();
}

void DisplayNode::takeStates()
{
  for (const auto& s : state_.takeAll()) {
    counters().samples_in++;
    if (!s.aligned) {
      continue;  // an estimate not yet aligned holds nothing
    }
    body_ = s;
    trace_.add({s.stamp_ns, s.p_W, s.q_WB});
  }
  if (truth_) {
    for (const auto& m : truth_->takeAll()) {
      counters().samples_in++;
      const TracePose p{m.stamp_ns, m.p_W, m.q_WB};
      body_true_ = p;
      true_trace_.add(p);
    }
  }
  const std::int64_t t = std::max(body_ ? body_->stamp_ns : 0, body_true_ ? body_true_->t_ns : 0);
  if ((body_ || body_true_) && t >= next_transforms_ns_) {
    publishTransforms(t);
    next_transforms_ns_ = t + static_cast<std::int64_t>(1e9 / config_.transforms_rate);
  }
  if ((body_ || body_true_) && t >= next_trajectory_ns_) {
    publishTrajectories(t);
    next_trajectory_ns_ = t + static_cast<std::int64_t>(1e9 / config_.trajectory_rate);
  }
}

void DisplayNode::publishTransforms(std::int64_t t_ns)
{
  foxglove::FrameTransforms m;
  if (body_) {
    m.transforms().push_back(transform(body_->stamp_ns, kWorldFrame, kBodyFrame, body_->p_W, body_->q_WB));
  }
  if (body_true_) {
    m.transforms().push_back(
        transform(body_true_->t_ns, kWorldFrame, kTrueBodyFrame, body_true_->p_W, body_true_->q_WB));
  }
  for (const auto& [frame, tf] : sensors_) {
    if (m.transforms().size() == 64) {
      break;  // foxglove/FrameTransforms.idl's bound
    }
    foxglove::FrameTransform now = tf;
    now.timestamp(toTime(t_ns));
    m.transforms().push_back(now);
  }
  transforms_.write(m);
  counters().samples_out++;
}

void DisplayNode::publishTrajectories(std::int64_t t_ns)
{
  const auto publish = [&](const Trace& trace, dds::Publisher<foxglove::PosesInFrame>& out) {
    if (trace.poses().empty()) {
      return;
    }
    foxglove::PosesInFrame m;
    m.timestamp(toTime(t_ns));
    m.frame_id(kWorldFrame);
    m.poses().reserve(trace.poses().size());
    for (const auto& p : trace.poses()) {
      m.poses().push_back(toPose(p.p_W, p.q_WB));
    }
    out.write(m);
    counters().samples_out++;
  };
  publish(trace_, trajectory_);
  publish(true_trace_, true_trajectory_);
}

void DisplayNode::takeDepth()
{
  for (const auto& scan : depth_.takeAll()) {
    counters().samples_in++;
    std::vector<Vector3> points;
    std::vector<Rgba> colours;
    points.reserve(scan.points().size());
    colours.reserve(scan.points().size());
    const double range = std::max(static_cast<double>(scan.max_range()), 1e-3);
    for (const auto& p : scan.points()) {
      const Vector3 v(p.x(), p.y(), p.z());
      if (!(v.norm() <= range)) {
        continue;  // beyond the range: no hit, only cleared space (msg::PointCloud)
      }
      points.push_back(v);
      colours.push_back(heightColour(range - v.norm(), 0.0, range));  // near: bright
    }
    const std::string frame = scan.frame_id().to_string();
    sensors_[frame] = transform(scan.header().stamp_ns(), kBodyFrame, frame, dds::toVector(scan.sensor_p_B()),
                                dds::toQuaternion(scan.sensor_q_BS()));
    depth_cloud_.write(toCloud(scan.header().stamp_ns(), frame, packPoints(points, colours)));
    counters().samples_out++;
  }
}

bool DisplayNode::followMap(double resolution, std::string_view topic)
{
  if (!follower_) {
    if (!(resolution > 0.0) || !std::isfinite(resolution)) {
      counters().errors++;
      spdlog::warn("{}: resolution {} m; ignored", topic, resolution);
      return false;
    }
    follower_.emplace(resolution);
    occupied_.emplace(resolution);
  }
  if (std::abs(resolution - occupied_->resolution()) > 1e-9) {
    counters().errors++;
    spdlog::warn("{}: resolution {} m, the map's is {} m; ignored", topic, resolution, occupied_->resolution());
    return false;
  }
  return true;
}

void DisplayNode::takeMap()
{
  for (const auto& m : snapshots_.takeAll()) {
    counters().samples_in++;
    if (!followMap(m.resolution(), dds::topics::kMapSnapshot.info.name)) {
      continue;
    }
    bool bad = false;
    if (const auto diff = follower_->snapshot(m.update_seq(), m.octree(), &bad)) {
      occupied_->apply(*diff);
    }
    if (bad) {
      counters().errors++;
      spdlog::warn("{}: snapshot {} is no OctoMap tree of resolution {} m; ignored",
                   dds::topics::kMapSnapshot.info.name, m.update_seq(), m.resolution());
    }
    map_ns_ = std::max(map_ns_, m.header().stamp_ns());
  }
  for (const auto& m : updates_.takeAll()) {
    counters().samples_in++;
    if (!followMap(m.resolution(), dds::topics::kMapUpdate.info.name)) {
      continue;
    }
    std::vector<mapping::VoxelChange> changes;
    changes.reserve(m.changes().size());
    for (const auto& c : m.changes()) {
      const auto state = c.state() == msg::VOXEL_OCCUPIED ? mapping::VoxelState::kOccupied
                         : c.state() == msg::VOXEL_FREE   ? mapping::VoxelState::kFree
                                                          : mapping::VoxelState::kUnknown;
      changes.push_back({geometry::VoxelIndex(c.ix(), c.iy(), c.iz()), state});
    }
    bool bad = false;
    occupied_->apply(follower_->update(m.update_seq(), std::move(changes), &bad));
    if (bad) {
      counters().errors++;
    }
    map_ns_ = std::max(map_ns_, m.header().stamp_ns());
  }
  if (!occupied_ || !occupied_->changed() || map_ns_ < next_map_ns_) {
    return;
  }
  next_map_ns_ = map_ns_ + static_cast<std::int64_t>(1e9 / config_.map_rate);
  const auto centres = occupied_->centres();
  double low = 0.0;
  double high = 1.0;
  if (!centres.empty()) {
    const auto [lo, hi] = std::minmax_element(centres.begin(), centres.end(),
                                              [](const Vector3& a, const Vector3& b) { return a.z() < b.z(); });
    low = lo->z();
    high = hi->z();
  }
  std::vector<Rgba> colours;
  colours.reserve(centres.size());
  for (const auto& c : centres) {
    colours.push_back(heightColour(c.z(), low, high));
  }
  map_.write(toCloud(map_ns_, kWorldFrame, packPoints(centres, colours)));
  counters().samples_out++;
}

void DisplayNode::takeScene()
{
  const auto goals = goals_.takeAll();
  counters().samples_in += goals.size();
  if (goals.empty() && scene_sent_) {
    return;  // the obstacles are drawn once before any goal, then with each goal
  }
  scene_sent_ = true;
  const std::int64_t t = goals.empty() ? 0 : goals.back().header().stamp_ns();
  foxglove::SceneUpdate update;
  for (std::size_t i = 0; i < obstacles_.size(); i += kShapesPerEntity) {
    auto e = entity(t, "obstacles/" + std::to_string(i / kShapesPerEntity));
    for (std::size_t k = i; k < std::min(obstacles_.size(), i + kShapesPerEntity); ++k) {
      addShape(e, obstacles_[k]);
    }
    update.entities().push_back(std::move(e));
  }
  if (!goals.empty()) {
    const msg::Goal& g = goals.back();
    auto e = entity(t, "goal");
    const Vector3 p = dds::toVector(g.p_W());
    addShape(e, goalShape(p, config_.goal_radius));
    foxglove::TextPrimitive label;
    label.pose(toPose(p + Vector3(0.0, 0.0, 2.0 * config_.goal_radius), Quaternion::identity()));
    label.billboard(true);
    label.font_size(14.0);
    label.scale_invariant(true);
    label.color(toColor({1.0, 1.0, 1.0, 1.0}));
    label.text("goal " + std::to_string(g.goal_id()));
    e.texts().push_back(label);
    update.entities().push_back(std::move(e));
  }
  scene_.write(update);
  counters().samples_out++;
}

void DisplayNode::takeTrajectories()
{
  for (const auto& m : trajectories_.takeAll()) {
    counters().samples_in++;
    std::string why;
    const auto t = dds::fromMessage(m, &why);
    if (!t) {
      counters().errors++;
      spdlog::warn("{}: trajectory {} not drawn: {}", dds::topics::kTrajectory.info.name, m.count(), why);
      continue;
    }
    foxglove::PosesInFrame out;
    out.timestamp(toTime(m.header().stamp_ns()));
    out.frame_id(kWorldFrame);
    for (const TracePose& p : planPoses(*t, kPlanPeriodS)) {
      out.poses().push_back(toPose(p.p_W, p.q_WB));
    }
    plan_.write(out);
    counters().samples_out++;
  }
}

void DisplayNode::takePaths()
{
  for (const auto& p : paths_.takeAll()) {
    counters().samples_in++;
    const bool ok = p.status() == msg::PLAN_OK;
    if (const auto line = events_.path(p.header().stamp_ns(), p.goal_id(), enumName("quad::msg::PlanStatus", p.status()),
                                       ok, p.cost(), p.waypoints_W().size())) {
      log(*line);
    }
    foxglove::PosesInFrame m;
    m.timestamp(toTime(p.header().stamp_ns()));
    m.frame_id(kWorldFrame);
    if (ok) {
      for (const auto& w : p.waypoints_W()) {
        m.poses().push_back(toPose(dds::toVector(w), Quaternion::identity()));
      }
    }
    path_.write(m);
    counters().samples_out++;
  }
}

void DisplayNode::takeLogLines()
{
  for (const auto& s : status_.takeAll()) {
    counters().samples_in++;
    const auto reason = s.failsafe_reason();
    if (const auto line = events_.status(
            s.header().stamp_ns(), enumName("quad::msg::ControlMode", s.mode()),
            reason == msg::FAILSAFE_NONE ? "" : enumName("quad::msg::FailsafeReason", reason),
            reason != msg::FAILSAFE_NONE && reason != msg::FAILSAFE_COMMANDED)) {
      log(*line);
    }
  }
  for (const auto& a : goal_acks_.takeAll()) {
    counters().samples_in++;
    log(events_.goalAnswer(a.header().stamp_ns(), a.goal_id(), a.accepted(), a.reason().to_string()));
  }
  for (const auto& a : command_acks_.takeAll()) {
    counters().samples_in++;
    log(events_.commandAnswer(a.header().stamp_ns(), enumName("quad::msg::CommandKind", a.kind()), a.accepted(),
                              a.reason().to_string()));
  }
  const auto classOf = [](msg::SimEventKind kind) {
    using C = EventLog::EventClass;
    if (kind == msg::SIM_EVENT_COLLISION || kind == msg::SIM_EVENT_CRASH) {
      return C::kCollision;
    }
    return kind == msg::SIM_EVENT_FAULT_APPLIED || kind == msg::SIM_EVENT_FAULT_CLEARED ? C::kFault : C::kOther;
  };
  for (const auto& e : sim_events_.takeAll()) {
    counters().samples_in++;
    log(events_.event(e.header().stamp_ns(), enumName("quad::msg::SimEventKind", e.kind()), e.detail().to_string(),
                      classOf(e.kind()), false));
  }
  for (const auto& e : fault_events_.takeAll()) {
    counters().samples_in++;
    log(events_.event(e.header().stamp_ns(), enumName("quad::msg::SimEventKind", e.kind()), e.detail().to_string(),
                      classOf(e.kind()), true));
  }
}

void DisplayNode::log(const LogLine& line)
{
  foxglove::Log m;
  m.timestamp(toTime(line.t_ns));
  switch (line.level) {
    case LogLine::Level::kDebug:
      m.level(foxglove::DEBUG);
      break;
    case LogLine::Level::kInfo:
      m.level(foxglove::INFO);
      break;
    case LogLine::Level::kWarning:
      m.level(foxglove::WARNING);
      break;
    case LogLine::Level::kError:
      m.level(foxglove::ERROR);
      break;
  }
  m.message(line.text.substr(0, 1024));
  m.name(line.source);
  log_.write(m);
  counters().samples_out++;
}

runtime::ModuleEntry displayModule() { return runtime::moduleEntry<DisplayNode>("display", displayNodeSchema(), displayConfigFrom); }

}  // namespace quad::display
