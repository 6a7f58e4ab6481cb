// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/observer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/liveliness.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/introspection/idl.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/runtime/node.hpp"
#include "quad/runtime/sim_clock.hpp"

namespace quad::launch {

namespace topics = dds::topics;

/// What the launcher follows from the start: the sim time, the vehicle's state (the truth,
/// which it alone reads in flight, to score the run), the estimator's state to score it,
/// the modules' heartbeats.
struct Observer::Sim {
  Sim(dds::Participant& p, const std::vector<std::uint32_t>& vehicles, std::int64_t state_period_ns)
      : state(p, topics::kSimState, nullptr, deep(p, topics::kSimState.info, state_period_ns)),
        estimate(p, topics::kEstimatedState, nullptr, deep(p, topics::kEstimatedState.info, state_period_ns)),
        clock(runtime::SimClockFollower::onlooker(p, vehicles, state_period_ns)),
        heartbeats(p, topics::kHeartbeat)
  {
  }
  /// Every state is scored, and the goal is reached at the first state within its tolerance
  /// in every run: a history deep enough for a launcher that falls behind for seconds. The
  /// controller's statuses too: its latched topic keeps the newest only, and each mode it
  /// passes through counts (a failsafe, the hover between take-off and mission).
  /// The states one a period of sim time, the same stamps of both (0: every one).
  static eprosima::fastdds::dds::DataReaderQos deep(dds::Participant& p, const dds::TopicInfo& topic,
                                                    std::int64_t period_ns = 0)
  {
    return *dds::readerQosWith(p, topic, 2048, period_ns);
  }
  dds::Subscriber<msg::VehicleState> state;
  dds::Subscriber<msg::EstimatedState> estimate;
  runtime::SimClockFollower clock;
  dds::Subscriber<msg::Heartbeat> heartbeats;
};

/// What flying a mission needs besides.
struct Observer::Endpoints {
  explicit Endpoints(dds::Participant& p)
      : goal(p, topics::kGoal),
        status(p, topics::kControlStatus, nullptr, Sim::deep(p, topics::kControlStatus.info)),
        path(p, topics::kPath, nullptr, Sim::deep(p, topics::kPath.info)),
        trajectory(p, topics::kTrajectory, nullptr, Sim::deep(p, topics::kTrajectory.info)),
        events(p, topics::kSimEvents),
        map_stats(p, topics::kMapStats),
        operator_beat(p, topics::kOperatorHeartbeat)
  {
  }
  dds::Publisher<msg::Goal> goal;
  dds::Subscriber<msg::ControlStatus> status;  // every one (Sim::deep)
  dds::Subscriber<msg::Path> path;  // every one (Sim::deep): each version counts
  dds::Subscriber<msg::Trajectory> trajectory;  // every one (Sim::deep): each its latency
  dds::Subscriber<msg::SimEvent> events;
  dds::Subscriber<msg::MapStats> map_stats;
  dds::Publisher<msg::Heartbeat> operator_beat;
  // The beats follow sim time, which stands while the lockstep clock waits: the writer's
  // liveliness (this process alive) is kept in wall time, as every module's heartbeat is.
  dds::LivelinessKeeper operator_alive{operator_beat};
};

/// The run's start, held until the readers that score it have matched their writers.
struct Observer::StartHold {
  StartHold(dds::Participant& p, std::size_t estimator_count) : estimators(estimator_count), reports(p, topics::kLockstep)
  {
  }
  std::size_t estimators;  // writers of estimates it waits for: one per vehicle's estimator
  dds::Publisher<msg::LockstepReport> reports;
  std::vector<std::uint32_t> released;  // vehicles whose start this observer no longer holds
};

/// One followed vehicle: where it is, how its estimator does, its mission once started.
struct Observer::Track {
  std::uint32_t id = 0;
  std::int64_t state_ns = -1;  // stamp of the newest state taken; -1 before the first
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  EstimateScore score;
  double radius = 0.0;
  std::unique_ptr<world::World> world;  // the tracker's: its address must not move
  std::unique_ptr<MissionTracker> tracker;
};

Observer::Observer(dds::ParticipantOptions options, std::vector<std::uint32_t> vehicles,
                   std::int64_t state_period_ns)
    : participant_(std::move(options)),
      ids_(vehicles.empty() ? std::vector<std::uint32_t>{participant_.options().vehicle_id} : std::move(vehicles)),
      sim_(std::make_unique<Sim>(participant_, ids_, state_period_ns))
{
  for (const std::uint32_t id : ids_) {
    tracks_.emplace_back().id = id;
  }
}

Observer::~Observer() = default;

void Observer::holdStart(std::size_t estimators)
{
  start_hold_ = std::make_unique<StartHold>(participant_, estimators);
}

bool Observer::holdingStart() const { return start_hold_ && start_hold_->released.size() < ids_.size(); }

void Observer::releaseStart()
{
  if (!start_hold_ || start_hold_->released.size() == ids_.size()) {
    return;
  }
  // The clock seen: the plant runs and waits at its first round, its writers discovered.
  if (!sim_->clock.seen() || sim_->state.matchedWriters() == 0 ||
      static_cast<std::size_t>(sim_->estimate.matchedWriters()) < start_hold_->estimators) {
    return;
  }
  for (const std::uint32_t id : ids_) {
    if (std::find(start_hold_->released.begin(), start_hold_->released.end(), id) != start_hold_->released.end()) {
      continue;
    }
    msg::LockstepReport report;
    report.header().stamp_ns(sim_->clock.ns());
    report.participant(runtime::kObserverParticipant);
    report.done_ns(runtime::kDoneForGoodNs);
    if (start_hold_->reports.writeFor(id, report)) {
      start_hold_->released.push_back(id);
    }  // else tried again with the next update
  }
}

Observer::Track* Observer::track(std::uint32_t id)
{
  const auto it = std::find_if(tracks_.begin(), tracks_.end(), [&](const Track& t) { return t.id == id; });
  return it == tracks_.end() ? nullptr : &*it;
}

std::size_t Observer::vehicleCount() const { return tracks_.size(); }
std::uint32_t Observer::vehicleId(std::size_t i) const { return tracks_.at(i).id; }
MissionTracker* Observer::mission(std::size_t i) { return tracks_.at(i).tracker.get(); }
const Eigen::Vector3d& Observer::position(std::size_t i) const { return tracks_.at(i).position; }
const EstimateScore& Observer::estimateScore(std::size_t i) const { return tracks_.at(i).score; }
std::optional<double> Observer::minimumSeparation() const { return min_separation_; }

bool Observer::missionsFinished() const
{
  return endpoints_ && std::all_of(tracks_.begin(), tracks_.end(), [](const Track& t) {
           return t.tracker == nullptr || t.tracker->finished();
         });
}

std::vector<std::string> Observer::missingWriters(const std::vector<std::string>& wanted) const
{
  const auto seen = participant_.remoteEndpoints();
  std::vector<std::string> missing;
  for (const auto& topic : wanted) {
    const bool live = std::any_of(seen.begin(), seen.end(),
                                  [&](const dds::RemoteEndpoint& e) { return e.writer && e.topic == topic; });
    if (!live) {
      missing.push_back(topic);
    }
  }
  return missing;
}

void Observer::startMission(const Mission& mission, std::vector<MissionVehicle> vehicles)
{
  endpoints_ = std::make_unique<Endpoints>(participant_);
  for (MissionVehicle& v : vehicles) {
    Track* t = track(v.id);
    if (t == nullptr) {
      throw std::invalid_argument("a mission for vehicle " + std::to_string(v.id) + ", which is not followed");
    }
    t->radius = v.radius;
    t->world = std::make_unique<world::World>(std::move(v.world));
    t->tracker = std::make_unique<MissionTracker>(mission, *t->world, v.radius);
    msg::Goal goal;
    goal.goal_id(1);
    goal.p_W(dds::toMessage(t->world->goal()));
    goal.yaw(std::numeric_limits<double>::quiet_NaN());
    goal.tolerance(mission.tolerance_m);
    goal.land(mission.land);
    endpoints_->goal.writeFor(v.id, goal);
  }
}

bool Observer::goalDelivered()
{
  if (!endpoints_) {
    return true;
  }
  const auto seen = participant_.remoteEndpoints();
  const auto readers = std::count_if(seen.begin(), seen.end(), [](const dds::RemoteEndpoint& e) {
    return !e.writer && e.topic == topics::kGoal.info.name;
  });
  return endpoints_->goal.matchedReaders() >= readers &&
         endpoints_->goal.waitForAcknowledgments(std::chrono::milliseconds(0));
}

namespace {
const introspection::EnumDef* controlModes()
{
  static const introspection::EnumDef* modes = introspection::quadSchema().findEnum("quad::msg::ControlMode");
  return modes;
}
std::string withoutPrefix(const std::string& name)
{
  return name.starts_with("CONTROL_") ? name.substr(8) : name;
}
}  // namespace

std::string noPathReason(int status)
{
  switch (status) {
    case msg::PLAN_GOAL_ENCLOSED:
      return "no path: known-occupied space seals the goal off";
    case msg::PLAN_START_ENCLOSED:
      return "no path: known-occupied space seals the vehicle in";
    case msg::PLAN_GOAL_BLOCKED:
      return "no path: the goal lies in an obstacle (or within the vehicle's radius and margin of one)";
    case msg::PLAN_OUT_OF_BOUNDS:
      return "no path: the goal is outside the planning bounds (the world's, less the margins, within the geofence)";
    default:
      return "";
  }
}

/// A failsafe, or the operator's landing or return, that ends the flight short of the goal, in
/// words; empty for the others (the planner's no-path has its own words, from the path's
/// status).
std::string flightEndedBy(msg::FailsafeReason reason, msg::ControlMode mode)
{
  switch (reason) {
    case msg::FAILSAFE_COMMANDED:
      return mode == msg::CONTROL_LAND     ? "the operator commanded a landing"
             : mode == msg::CONTROL_RETURN ? "the operator commanded a return to launch"
                                           : "";
    case msg::FAILSAFE_GEOFENCE:
      return "the vehicle left the geofence";
    case msg::FAILSAFE_BATTERY_LOW:
      return "the battery ran low";
    case msg::FAILSAFE_BATTERY_CRITICAL:
      return "the battery failed (critical)";
    case msg::FAILSAFE_LINK_LOST:
      return "the operator's link was lost";
    case msg::FAILSAFE_STATE_STALE:
      return "the vehicle state was lost";
    case msg::FAILSAFE_ESTIMATE_UNCERTAIN:
      return "the state estimate grew uncertain";
    default:
      return "";
  }
}

std::string controlModeName(int mode)
{
  const auto* modes = controlModes();
  const auto i = static_cast<std::size_t>(mode);
  if (modes == nullptr || mode < 0 || i >= modes->enumerators.size()) {
    return "MODE_" + std::to_string(mode);
  }
  return withoutPrefix(modes->enumerators[i]);
}

std::vector<std::string> controlModeNames()
{
  std::vector<std::string> out;
  if (const auto* modes = controlModes()) {
    for (const auto& e : modes->enumerators) {
      out.push_back(withoutPrefix(e));
    }
  }
  return out;
}

std::vector<ModuleBeat> Observer::takeHeartbeats()
{
  std::vector<ModuleBeat> beats;
  // Every module's, whichever vehicle it serves.
  while (const auto hb = sim_->heartbeats.takeAnyVehicle()) {
    const bool running = hb->state() == msg::MODULE_RUNNING || hb->state() == msg::MODULE_DEGRADED;
    beats.push_back({hb->module_name().to_string(), hb->pid(), running, hb->header().stamp_ns()});
  }
  return beats;
}

std::int64_t Observer::simTimeNs() const { return sim_->clock.ns(); }

void Observer::onState(Track& v, std::int64_t stamp_ns, const Eigen::Vector3d& p, const geometry::Quaternion& q,
                       const Eigen::Vector3d& v_W)
{
  v.state_ns = stamp_ns;
  v.position = p;
  last_state_ns_ = common::steadyTimeNs();
  if (first_state_ns_ == 0) {
    first_state_ns_ = last_state_ns_;
  }
  v.score.onTruth(stamp_ns, p, q, v_W);
  if (!v.tracker) {
    return;
  }
  v.tracker->onState(common::toSeconds(stamp_ns), p);
  // The plant sends every vehicle's state of one step with one stamp.
  for (const Track& other : tracks_) {
    if (&other != &v && other.tracker && other.state_ns == stamp_ns) {
      const double separation = (p - other.position).norm() - v.radius - other.radius;
      min_separation_ = std::min(min_separation_.value_or(separation), separation);
    }
  }
}

void Observer::update()
{
  sim_->clock.update();
  releaseStart();
  for (const auto& s : sim_->state.takeAll(ids_)) {
    // Only states the sim clock vouches for, in order: one stamped ahead of it (a bad input)
    // would end the mission by its timeout, an old one would teleport the vehicle.
    Track& v = *track(s.header().vehicle_id());
    const Eigen::Vector3d p = dds::toVector(s.p_W());
    if (!sim_->clock.vouchesFor(s.header().stamp_ns()) || s.header().stamp_ns() < v.state_ns || !p.allFinite()) {
      continue;
    }
    onState(v, s.header().stamp_ns(), p, dds::toQuaternion(s.q_WB()), dds::toVector(s.v_W()));
  }
  for (const auto& e : sim_->estimate.takeAll(ids_)) {
    Track& v = *track(e.header().vehicle_id());
    v.score.onEstimate(e.header().stamp_ns(), dds::toVector(e.p_W()), dds::toQuaternion(e.q_WB()),
                           dds::toVector(e.p_std()), e.aligned());
  }
  if (!endpoints_) {
    return;
  }
  // Each sample goes to its vehicle's mission; a vehicle without one has none to feed.
  const auto missionOf = [&](const auto& sample) { return track(sample.header().vehicle_id())->tracker.get(); };
  for (const auto& s : endpoints_->status.takeAll(ids_)) {
    if (auto* m = missionOf(s)) {
      m->onMode(common::toSeconds(s.header().stamp_ns()), controlModeName(static_cast<int>(s.mode())),
                flightEndedBy(s.failsafe_reason(), s.mode()));
    }
  }
  for (const auto& p : endpoints_->path.takeAll(ids_)) {
    if (auto* m = missionOf(p)) {
      m->onPath(common::toSeconds(p.header().stamp_ns()), p.version(), noPathReason(p.status()));
      m->onPathOverruns(p.overruns());
    }
  }
  for (const auto& t : endpoints_->trajectory.takeAll(ids_)) {
    if (auto* m = missionOf(t); m != nullptr && t.path_version() != 0 && t.depth_stamp_ns() >= 0) {
      m->onTrajectory(common::toSeconds(t.header().stamp_ns()), common::toSeconds(t.depth_stamp_ns()));
    }
  }
  for (const auto& e : endpoints_->events.takeAll(ids_)) {
    if (auto* m = missionOf(e); m != nullptr && e.kind() == msg::SIM_EVENT_COLLISION) {
      m->onCollision(common::toSeconds(e.header().stamp_ns()));
    } else if (m != nullptr && e.kind() == msg::SIM_EVENT_CRASH) {
      m->onCrash(common::toSeconds(e.header().stamp_ns()), e.detail().to_string());
    }
  }
  for (const auto& m : endpoints_->map_stats.takeAll(ids_)) {
    if (auto* mission = missionOf(m)) {
      mission->onMapStats(m.overruns());
    }
  }
  // The estimator is scored up to the mission's end, however late that end is heard beside
  // the estimates taken meanwhile (the state or mode that ended it may come in a later take
  // than estimates stamped after it), and however late the stack is stopped.
  for (Track& v : tracks_) {
    if (v.tracker && v.tracker->finished()) {
      v.score.endAt(common::toNanoseconds(v.tracker->endTime()));
    }
  }
  constexpr std::int64_t kOperatorBeatNs = 500'000'000;  // the contract's 2 Hz, in sim time
  const std::int64_t now_ns = sim_->clock.ns();
  if (operator_link_ && now_ns >= next_operator_beat_ns_) {
    for (const std::uint32_t id : ids_) {
      endpoints_->operator_beat.writeFor(id, runtime::processHeartbeat("operator", msg::MODULE_RUNNING, now_ns));
    }
    next_operator_beat_ns_ = now_ns + kOperatorBeatNs;
  }
}

}  // namespace quad::launch
