// SPDX-License-Identifier: BSD-3-Clause
#include "planning_node.hpp"

#include "quad/common/layout.hpp"

#include <algorithm>
#include <limits>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/sim_period_filter.hpp"
#include "quad/planning/replan.hpp"
#include "quad/vehicle/vehicle.hpp"
#include "quad/world/world_file.hpp"

namespace quad::planning {

namespace {
/// How long an update may trail the mapper's lockstep report before it counts as lost [ns]:
/// ten heartbeat periods of the reliable QoS (configs/dds/quad_qos.xml).
constexpr std::int64_t kLostUpdateGraceNs = 1'000'000'000;
/// How long a planner that joined after the mapper's first update holds lockstep for the
/// snapshot that fills the gap [ns of wall time].
constexpr std::int64_t kJoiningHoldNs = 2'000'000'000;
/// How many more depth frames a map update may count than the clock's newest sample here:
/// the clock's samples lag the mapper's updates by a repair at most (2 s of the 10 Hz camera).
constexpr std::uint64_t kFramesAheadOfClock = 20;

Occupancy fromMessage(msg::VoxelState s)
{
  switch (s) {
    case msg::VOXEL_FREE:
      return Occupancy::kFree;
    case msg::VOXEL_OCCUPIED:
      return Occupancy::kOccupied;
    default:
      return Occupancy::kUnknown;
  }
}

msg::PlanStatus toMessage(PlanStatus s)
{
  switch (s) {
    case PlanStatus::kOk:
      return msg::PLAN_OK;
    case PlanStatus::kNoPath:
      return msg::PLAN_NO_PATH;
    case PlanStatus::kStartBlocked:
      return msg::PLAN_START_BLOCKED;
    case PlanStatus::kGoalBlocked:
      return msg::PLAN_GOAL_BLOCKED;
    case PlanStatus::kOutOfBounds:
      return msg::PLAN_OUT_OF_BOUNDS;
    case PlanStatus::kNoGoal:
      return msg::PLAN_NO_GOAL;
    case PlanStatus::kBudgetExceeded:
      return msg::PLAN_BUDGET_EXCEEDED;
    case PlanStatus::kGoalEnclosed:
      return msg::PLAN_GOAL_ENCLOSED;
    case PlanStatus::kStartEnclosed:
      return msg::PLAN_START_ENCLOSED;
  }
  return msg::PLAN_NO_PATH;
}

}  // namespace

const common::ParamTable<PlanningNodeConfig>& planningNodeTable()
{
  using N = PlanningNodeConfig;
  static const common::ParamTable<N> table = [] {
    common::ParamTable<N> t;
    t.include(planningTable(), [](N& n) -> PlanningParams& { return n; });
    runtime::declareStateSource(t, [](N& n) -> runtime::StateSource& { return n.state_source; });
    return t;
  }();
  return table;
}

common::ParamSchema planningNodeSchema() { return planningNodeTable().schema(); }

PlanningNodeConfig planningConfigFrom(const common::Params& p)
{
  PlanningNodeConfig c = planningNodeTable().read(p, common::configDir());
  static_cast<PlanningParams&>(c) = planningParamsOf(p);
  const world::World world = world::loadWorld(c.world_file);
  fitToWorld(c, world.bounds().min, world.bounds().max, vehicle::loadVehicle(c.vehicle_file).radius, p.origin());
  // Readers judge the path stale after the contract's deadline: repeat it twice within it.
  const double deadline = dds::topics::kPath.info.stale_after_s;
  if (c.republish_period_s > deadline / 2.0) {
    throw common::ConfigError({common::configProblem(p.origin(), "republish_period", c.republish_period_s,
                                                     "above half the " + std::string(dds::topics::kPath.info.name) +
                                                         " deadline (" + common::formatValue(deadline) +
                                                         " s): readers would judge the path stale")});
  }
  return c;
}

PlanningNode::PlanningNode(PlanningNodeConfig config, dds::Participant handle)
    : Node("planning", std::move(handle)),
      config_(std::move(config)),
      planner_(Lattice(geometry::VoxelGrid(config_.resolution), config_.bounds_min, config_.bounds_max), config_.planner),
      follower_(config_.resolution),
      updates_(participant(), dds::topics::kMapUpdate, waker()),
      snapshots_(participant(), dds::topics::kMapSnapshot, waker()),
      // In lockstep the clock runs on while a replan works, up to the path's budget: the
      // states that come meanwhile wait here, none replaced by a newer one (each is handled
      // in turn, with the map due by its time).
      state_(participant(), config_.state_source, waker(), runtime::kHeldStates, runtime::statePeriodNs(config_.state_rate)),
      goal_(participant(), dds::topics::kGoal, waker()),
      // Every path of every vehicle, none replaced by a newer before it is taken: the one in
      // effect at a replan may be older than the newest heard (kPathEffectDelayNs).
      fleet_paths_(participant(), dds::topics::kPath, waker(),
                   dds::withDepth(participant().readerQos(dds::topics::kPath.info.qos_profile), 64),
                   dds::kEveryVehicle),
      reports_(participant(), dds::topics::kLockstep),
      path_(participant(), dds::topics::kPath),
      goal_acks_(participant(), dds::topics::kGoalAck),
      mapper_(participant(), "mapping", waker()),
      lockstep_(participant(), "planning"),
      mapper_lapse_(mapper_.leaseNs().value_or(0)),
      deconfliction_(participant().options().vehicle_id, config_.fleet, config_.planner.vehicle_radius,
                     config_.planner.vehicle_radius - config_.safety_margin)
{
  followSimClock(runtime::kHeldStates);  // every sample: the depth frames due at each state's time
  current_.depth_stamp_ns(depth_stamp_ns_);
  spdlog::info("planning: lattice {} cells at {} m, inflation {} m", planner_.lattice().size(), config_.resolution,
               config_.planner.vehicle_radius);
}

void PlanningNode::answerGoal(std::uint32_t goal_id, bool accepted, const std::string& reason)
{
  msg::GoalAck ack;
  ack.header().stamp_ns(now_ns_);
  ack.goal_id(goal_id);
  ack.accepted(accepted);
  ack.reason(reason.substr(0, 256));
  goal_acks_.write(ack);
  counters().samples_out++;
}

void PlanningNode::takeStates()
{
  for (auto& s : state_.takeAll()) {
    // The sim time and the start of every replan: a state stamped past the clock, older than
    // the last, or not finite is a bad input (a time an hour ahead stopped every replan). An
    // estimate still aligning gives the time only.
    const std::int64_t last = held_states_.empty() ? now_ns_ : held_states_.back().stamp_ns;
    if (!s.p_W.allFinite() || s.stamp_ns < last || (simClock().seen() && !simClock().vouchesFor(s.stamp_ns))) {
      counters().errors++;
      spdlog::warn("{}: sample seq {} rejected: position not finite, or stamp {:.3f} s out of order or "
                   "past the sim clock ({:.3f} s)", state_.topic().name,
                   s.seq, common::toSeconds(s.stamp_ns), common::toSeconds(simClock().ns()));
      continue;
    }
    held_states_.push_back(std::move(s));
  }
}

std::uint64_t PlanningNode::framesDueAt(std::int64_t at_ns)
{
  // In lockstep an update takes effect at its due time, the mapper's budget after its depth
  // frame: the frames due are those the clock had published the budget earlier. In real time
  // every update as it comes.
  return lockstep() ? simClock().depthFramesAt(at_ns - participant().options().mapBudgetNs())
                    : simClock().depthFrames();
}

void PlanningNode::takeMapSamples()
{
  while (auto s = snapshots_.take()) {
    const std::int64_t stamp_ns = s->header().stamp_ns();
    // Due at its stamp. The mapper stamps its snapshots in order: a held one stamped after
    // the one that follows it is covered by that one, and let go. Stamped more than the
    // mapper's budget after it, it was damaged on the way (one bit flipped in its stamp, say);
    // within the budget it is the last one of a mapper that restarted since, whose resumed map
    // is stamped with the scan that snapshot was due the budget after.
    const std::uint64_t seq = s->update_seq();
    held_snapshots_.holdRising(stamp_ns, std::move(*s), [&](const msg::MapSnapshot& held) {
      const std::int64_t held_ns = held.header().stamp_ns();
      if (held_ns - stamp_ns <= participant().options().mapBudgetNs()) {
        return;
      }
      counters().errors++;
      spdlog::warn("{}: snapshot {} stamped {} s, after snapshot {} that follows it ({} s): refused",
                   dds::topics::kMapSnapshot.info.name, held.update_seq(), common::toSeconds(held_ns), seq,
                   common::toSeconds(stamp_ns));
    });
  }
  for (auto& u : updates_.takeAll()) {
    counters().samples_in++;
    // A count of depth frames the clock has not reached, by more than its samples can lag
    // the mapper's, is a bad input: held until the clock gets there, it would hold every
    // later update back for ever (seen: one bit flipped on the link, 2^31 frames more).
    // Refused, it is a lost update: a gap until the next snapshot.
    if (simClock().seen() && u.depth_frames() > simClock().depthFrames() + kFramesAheadOfClock) {
      counters().errors++;
      update_lost_ = true;
      spdlog::warn("{}: update {} counts {} depth frames, the clock {}: refused; a gap until the next snapshot",
                   dds::topics::kMapUpdate.info.name, u.update_seq(), u.depth_frames(), simClock().depthFrames());
      continue;
    }
    // Due once the depth frames due reach the ones it accounts for (framesDueAt). The
    // mapper's counts never fall: a held update that counts more depth frames than the one
    // after it was damaged on the way. Held until the clock got there, it would hold the
    // updates after it back, and in lockstep the clock with them, for good (one bit flipped
    // low in the count, within the clock's lead). Refused, it is a lost update.
    const auto frames = static_cast<std::int64_t>(std::min<std::uint64_t>(u.depth_frames(), kMaxFramesDue));
    const std::uint64_t seq = u.update_seq();
    held_updates_.holdRising(frames, std::move(u), [&](const msg::MapUpdate& damaged) {
      counters().errors++;
      update_lost_ = true;
      spdlog::warn("{}: update {} counts {} depth frames, more than update {} after it ({}): refused; a gap until "
                   "the next snapshot",
                   dds::topics::kMapUpdate.info.name, damaged.update_seq(), damaged.depth_frames(), seq, frames);
    });
  }
}

void PlanningNode::applyMapDue(std::int64_t at_ns)
{
  // Snapshots first: one sent with the updates it contains must not undo newer ones. Taking
  // each when it is due by the time of the state handled, not when it came, makes the map a
  // replan sees the same in every run (the mapper works ahead of the clock up to its budget,
  // and the clock runs ahead of this planner up to the path's).
  held_snapshots_.release(lockstep() ? at_ns : std::numeric_limits<std::int64_t>::max(),
                          [this](const msg::MapSnapshot& snapshot) { applySnapshot(snapshot); });
  // In real time every update as it comes.
  const std::uint64_t frames_due = lockstep() ? framesDueAt(at_ns) : kMaxFramesDue;
  held_updates_.release(static_cast<std::int64_t>(std::min(frames_due, kMaxFramesDue)),
                        [this](const msg::MapUpdate& u) { applyUpdate(u); });
}

void PlanningNode::applySnapshot(const msg::MapSnapshot& snapshot)
{
  bool bad = false;
  const auto diff = follower_.snapshot(snapshot.update_seq(), snapshot.octree(), &bad);
  if (bad) {
    counters().errors++;
    spdlog::warn("{}: snapshot {} is not a map at {} m; ignored",
                 dds::topics::kMapSnapshot.info.name, snapshot.update_seq(), config_.resolution);
  }
  if (!diff) {
    return;
  }
  for (const auto& c : *diff) {
    pending_.emplace_back(c.index, static_cast<Occupancy>(c.state));
  }
  spdlog::info("planning: caught up from snapshot {} and {} later updates ({} voxels differed)", snapshot.update_seq(),
               follower_.replayed(), diff->size());
}

void PlanningNode::applyUpdate(const msg::MapUpdate& update)
{
  if (std::abs(update.resolution() - config_.resolution) > 1e-9) {
    counters().errors++;
    spdlog::warn("{}: resolution {} m, the lattice's is {} m; ignored",
                 dds::topics::kMapUpdate.info.name, update.resolution(),
                 config_.resolution);
    return;
  }
  const std::uint64_t before = follower_.appliedSeq();
  if (update.update_seq() > before + 1) {
    if (before == 0) {
      spdlog::info("{}: joined at update {}; the rest comes with the next snapshot",
                   dds::topics::kMapUpdate.info.name, update.update_seq());
    } else {
      spdlog::warn("{}: {} follows {}: a gap until the next snapshot",
                   dds::topics::kMapUpdate.info.name, update.update_seq(), before);
    }
  }
  std::vector<mapping::VoxelChange> changes;
  changes.reserve(update.changes().size());
  for (const auto& c : update.changes()) {
    changes.push_back({VoxelIndex(c.ix(), c.iy(), c.iz()), static_cast<mapping::VoxelState>(fromMessage(c.state()))});
  }
  const std::uint64_t gaps = follower_.gaps();
  const std::uint64_t restarts = follower_.restarts();
  bool bad = false;
  for (const auto& c : follower_.update(update.update_seq(), std::move(changes), &bad)) {
    pending_.emplace_back(c.index, static_cast<Occupancy>(c.state));
  }
  if (follower_.restarts() > restarts) {
    spdlog::warn("{}: numbered from 1 again: the mapper started again with an empty map (no checkpoint); "
                 "what it knew is gone, and planning starts over from what it sees now",
                 dds::topics::kMapUpdate.info.name);
  }
  if (bad) {
    counters().errors++;
    spdlog::warn("{}: a snapshot kept for a gap is not a map at {} m; ignored",
                 dds::topics::kMapSnapshot.info.name, config_.resolution);
  } else if (follower_.gaps() > gaps && !follower_.gapOpen()) {
    spdlog::info("planning: the gap before update {} filled from a snapshot that came ahead of it",
                 update.update_seq());
  }
  // Covered by a snapshot or applied now, what it accounts for is in the map.
  frames_applied_ = std::max(frames_applied_, update.depth_frames());
  depth_stamp_ns_ = std::max(depth_stamp_ns_, update.depth_stamp_ns());
  update_lost_ = false;
}

void PlanningNode::applyPending()
{
  // Each voxel's newest state, in the order of the voxels' indices: the graph a replan
  // searches (and its ties) is then the same however the changes were split into updates
  // and snapshots, and whenever each came.
  std::stable_sort(pending_.begin(), pending_.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.first.data(), a.first.data() + 3, b.first.data(), b.first.data() + 3);
  });
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    if (i + 1 == pending_.size() || pending_[i + 1].first != pending_[i].first) {
      planner_.updateVoxel(pending_[i].first, pending_[i].second);
    }
  }
  pending_.clear();
}

void PlanningNode::noticeLostUpdate(std::int64_t at_ns)
{
  while (auto r = reports_.take()) {
    if (r->participant() == "mapping") {
      mapper_done_ns_ = std::max(mapper_done_ns_, r->done_ns());
    }
  }
  // The mapper reports a time done once every update due by then is out; reliable
  // delivery repairs a lost datagram within a few 100 ms heartbeats. An update still missing
  // a second after that report was corrupted past recognition (another vehicle's id, a wrong
  // count) and will not come: without this, lockstep would wait for it for ever.
  if (!lockstep() || update_lost_ || frames_applied_ >= framesDueAt(at_ns) || mapper_done_ns_ < at_ns) {
    mapper_done_wall_ns_ = 0;
    return;
  }
  const std::int64_t now = common::steadyTimeNs();
  if (mapper_done_wall_ns_ == 0) {
    mapper_done_wall_ns_ = now;
  } else if (now - mapper_done_wall_ns_ > kLostUpdateGraceNs) {
    update_lost_ = true;
    counters().errors++;
    spdlog::warn("{}: the mapper was done up to {:.3f} s a second ago and the update for depth frame {} "
                 "never came: lost; a gap until the next snapshot", dds::topics::kMapUpdate.info.name,
                 common::toSeconds(mapper_done_ns_), framesDueAt(at_ns));
  }
}

void PlanningNode::publish(std::int64_t t_ns, bool changed)
{
  if (changed) {
    current_.version(++version_);
  }
  // Due, and stamped, the path's budget after the state it answers; in lockstep an overrun
  // when the clock got there first (it waits there for this path).
  const std::int64_t due_ns = t_ns + participant().options().pathBudgetNs();
  if (overran(due_ns, fmt::format("path {}", version_))) {
    ++overruns_;
  }
  current_.overruns(overruns_);
  current_.header().stamp_ns(due_ns);
  path_.write(current_);
  counters().samples_out++;
  next_publish_ns_ = t_ns + common::toNanoseconds(config_.republish_period_s);
}

void PlanningNode::takeFleetPaths()
{
  while (auto p = fleet_paths_.takeAnyVehicle()) {
    std::vector<Vector3> waypoints;
    for (const auto& w : p->waypoints_W()) {
      waypoints.push_back(dds::toVector(w));
    }
    if (std::all_of(waypoints.begin(), waypoints.end(), [](const Vector3& w) { return w.allFinite(); })) {
      deconfliction_.onPath(p->header().vehicle_id(), p->header().stamp_ns(), std::move(waypoints));
    }
  }
}

void PlanningNode::applyKeepOut(std::int64_t t_ns)
{
  takeFleetPaths();
  const std::vector<std::uint32_t> giving_way = deconfliction_.yieldingTo(t_ns);
  if (giving_way != giving_way_to_) {
    giving_way_to_ = giving_way;
    spdlog::info("planning: giving way to {}", giving_way.empty()       ? std::string("no vehicle")
                                               : giving_way.size() == 1 ? fmt::format("vehicle {}", giving_way.front())
                                                                        : fmt::format("vehicles {}", fmt::join(giving_way, ", ")));
  }
  planner_.setKeepOut(deconfliction_.keepOut(planner_.lattice(), t_ns));
}

void PlanningNode::replan(std::int64_t t_ns)
{
  if (!goal_id_ || !position_) {
    return;
  }
  // From where the vehicle will be when the path takes effect, the budget on at the state's
  // velocity: the path starts at the vehicle, not the budget behind it.
  const Vector3 from = *position_ + velocity_ * common::toSeconds(participant().options().pathBudgetNs());
  applyPending();
  applyKeepOut(t_ns);
  const std::int64_t begin = common::steadyTimeNs();
  // Outside the lattice, the controller, not the planner, answers for the vehicle (replan.hpp).
  const Replan r = replanFrom(planner_, from, config_, deconfliction_.clearance());
  const double seconds = common::toSeconds(common::steadyTimeNs() - begin);
  if (r.result.status == PlanStatus::kBudgetExceeded) {
    return;  // keep the previous path; the search continues next cycle
  }
  // Publish a new version only when the path changed meaningfully.
  const bool changed = changedPath(r, previous_, config_.resolution);
  previous_ = r;
  current_.goal_id(*goal_id_);
  current_.status(toMessage(r.result.status));
  current_.cost(r.result.status == PlanStatus::kOk ? r.result.cost : -1.0);
  current_.known_free_m(r.known_free);
  current_.depth_stamp_ns(depth_stamp_ns_);
  current_.expansions(r.result.expansions);
  current_.replan_time_s(seconds);
  current_.waypoints_W().clear();
  for (const auto& w : r.waypoints) {
    current_.waypoints_W().push_back(dds::toMessage(w));
  }
  if (changed) {
    spdlog::info("planning: path {} {}: {} waypoints, cost {:.2f} m, known free {:.1f} m, {} expansions, {:.1f} ms",
                 version_ + 1, toString(r.result.status), r.waypoints.size(), r.result.cost, r.known_free,
                 r.result.expansions, seconds * 1e3);
  }
  if (changed || t_ns >= next_publish_ns_) {
    publish(t_ns, changed);
  }
}

void PlanningNode::takeGoal(const msg::Goal& g)
{
  const Vector3 p = dds::toVector(g.p_W());
  const auto cell = p.allFinite() ? planner_.lattice().cellAt(p) : std::nullopt;
  if (!cell) {
    counters().errors++;
    const Vector3& lo = config_.bounds_min;
    const Vector3& hi = config_.bounds_max;
    const std::string why = fmt::format(
        "goal {} at ({}, {}, {}) is outside the planning bounds ({:g}, {:g}, {:g}) ... ({:g}, {:g}, {:g}); refused{}",
        g.goal_id(), p.x(), p.y(), p.z(), lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(),
        goal_id_ ? fmt::format(" (still flying to goal {})", *goal_id_) : "");
    spdlog::error("{}: {}", dds::topics::kGoal.info.name, why);
    answerGoal(g.goal_id(), false, why);
    if (goal_id_) {
      return;  // a refused goal does not replace the one being flown
    }
    current_.status(msg::PLAN_OUT_OF_BOUNDS);
    current_.goal_id(g.goal_id());
    current_.waypoints_W().clear();
    publish(now_ns_, true);
    return;
  }
  goal_id_ = g.goal_id();
  planner_.setGoal(*cell);
  goal_changed_ = true;
  spdlog::info("planning: goal {} at ({}, {}, {})", g.goal_id(), p.x(), p.y(), p.z());
  answerGoal(g.goal_id(), true, fmt::format("planning to goal {} at ({}, {}, {})", g.goal_id(), p.x(), p.y(), p.z()));
}

bool PlanningNode::handleState(const runtime::StateSample& s)
{
  const std::int64_t t = s.stamp_ns;
  // The frames due at t come from the clock's samples up to t, sent reliably on another topic
  // than the state: a state that came first waits for the clock of its time.
  if (lockstep() && simClock().ns() < t) {
    waiting_for_ = fmt::format("the clock's sample of the state's time {:.3f} s", common::toSeconds(t));
    return false;
  }
  // In lockstep a replan sees every map update due by its state's time, so that runs repeat;
  // the clock waits at the path's due time for what is not handled by then. A lost update is
  // not waited for (it never comes).
  applyMapDue(t);
  noticeLostUpdate(t);
  const std::uint64_t frames_due = framesDueAt(t);
  const bool caught_up = !lockstep() || frames_applied_ >= frames_due || update_lost_;
  // Joined after the mapper's first update (it depends on when this participant matched), the
  // planner waits for the snapshot that fills the gap (latched, it comes): the replans then
  // fall on the states they would have without the gap. Not for ever: a map too large for a
  // snapshot would never come.
  const bool joining = lockstep() && follower_.appliedSeq() == 0 && frames_due > 0 && held_snapshots_.empty();
  const std::int64_t wall_ns = common::steadyTimeNs();
  if (!joining) {
    joining_since_ns_ = 0;
  } else if (joining_since_ns_ == 0) {
    joining_since_ns_ = wall_ns;
  }
  if (!caught_up || (joining && wall_ns - joining_since_ns_ < kJoiningHoldNs)) {
    waiting_for_ = caught_up ? std::string("joined after the mapper's first update: waiting for its snapshot")
                             : fmt::format("map updates cover {} of the {} depth frames due at the state of {:.3f} s",
                                           frames_applied_, frames_due, common::toSeconds(t));
    return false;
  }
  if (s.aligned) {
    position_ = s.p_W;
    velocity_ = s.v_W;
  }
  now_ns_ = t;
  goals_due_.release(now_ns_, [this](const msg::Goal& g) { takeGoal(g); });
  // A planner that joined late or missed an update plans nothing until a snapshot fills the
  // gap: a path through what it does not know the mapper saw could hit it. Without paths the
  // controller holds position.
  // A mapper that stopped (killed, stopped, starved) leaves the map behind what the camera
  // saw: flying it would meet what only the camera knows.
  const bool map_whole = !follower_.gapOpen() && !update_lost_ && !(follower_.appliedSeq() == 0 && frames_due > 0) &&
                         frames_due <= frames_applied_ + config_.map_frames_behind;
  if (map_whole != map_whole_) {
    map_whole_ = map_whole;
    if (map_whole) {
      spdlog::info("planning: the map is whole again; planning");
    } else {
      spdlog::warn("planning: the map lags the camera ({} of {} depth frames{}): no paths until it catches up",
                   frames_applied_, frames_due,
                   follower_.gapOpen() || update_lost_ ? ", a gap in the updates" : "");
    }
  }
  // The mapper's heartbeat losing its liveliness (stopped, killed or cut off; a busy mapper
  // keeps it) withdraws the path: the controller holds on a path that is not PLAN_OK,
  // where the second it would fly on before its path timeout is a second into what only the
  // camera saw. A map that merely lags (a slow mapper catching up) only stops the replans.
  // In lockstep a lapse counts once it has lasted half a second of sim time (MapperLapse).
  const bool mapper_lost = mapper_lapse_.update(mapper_.update() == dds::ModuleWatch::State::kLost,
                                                simClock().ns(), lockstep());
  if (mapper_lost != mapper_lost_) {
    mapper_lost_ = mapper_lost;
    if (mapper_lost) {
      spdlog::warn("planning: the mapper's heartbeat lost its liveliness (stopped, killed or cut off): "
                   "path withdrawn, the vehicle holds");
    } else {
      spdlog::info("planning: the mapper is alive again");
    }
  }
  if (mapper_lost && goal_id_ && (current_.status() != msg::PLAN_MAPPER_LOST || now_ns_ >= next_publish_ns_)) {
    const bool changed = current_.status() != msg::PLAN_MAPPER_LOST;
    current_.goal_id(*goal_id_);
    current_.status(msg::PLAN_MAPPER_LOST);
    current_.cost(-1.0);
    current_.expansions(0);
    current_.replan_time_s(0.0);
    current_.waypoints_W().clear();
    publish(now_ns_, changed);
  }
  if (!goal_id_) {
    applyPending();  // no search to keep in step: the map only
  }
  if (goal_id_ && position_ && map_whole && !mapper_lost && (goal_changed_ || now_ns_ >= next_replan_ns_)) {
    replan(now_ns_);
    goal_changed_ = false;
    next_replan_ns_ = now_ns_ + common::toNanoseconds(config_.replan_period_s);
  }
  return true;
}

std::int64_t PlanningNode::handledNs() const
{
  // The last state handled, and when one a period is read the rest of its period (no other state
  // of it comes); the clock's time once no state is held and none was sent since (a fault
  // dropped them): nothing before then can still ask for a path.
  const std::int64_t period = runtime::statePeriodNs(config_.state_rate);
  std::int64_t through = period > 0 ? dds::simPeriodWindowEnd(now_ns_, period) - 1 : now_ns_;
  if (!held_states_.empty()) {
    through = std::min(through, held_states_.front().stamp_ns - 1);  // the first state, held
  }
  const bool all_handled = held_states_.empty() && simClock().lastStateSentNs() <= through;
  return all_handled ? std::max(through, simClock().ns()) : through;
}

void PlanningNode::reportLockstep()
{
  if (!lockstep() || !simClock().seen()) {
    return;
  }
  // A state handled at t answers by t plus the budget: done up to then. With the budget 0 the
  // clock waits every round for the state of its time to be handled.
  const std::int64_t budget = participant().options().pathBudgetNs();
  const std::int64_t done = handledNs() + budget;
  if (done < simClock().ns()) {
    lockstep_.holding(simClock().ns(), [&] {
      return !held_states_.empty() ? waiting_for_
                                    : fmt::format("no vehicle state of that time yet (the last at {:.3f} s)",
                                                  common::toSeconds(now_ns_));
    });
  }
  lockstep_.reportAhead(done, simClock().ns(), budget);
}

void PlanningNode::onWake()
{
  // An update refused on receipt (its payload broke the IDL) is lost for good: the middleware
  // counts it delivered and never sends it again. The follower sees the gap at the next
  // update and waits for a snapshot; until then what the lost one accounted for is unknown.
  const std::uint64_t refused = dds::rejectedPayloadCount(dds::MessageTraits<msg::MapUpdate>::kTypeName);
  if (refused > refused_updates_) {
    refused_updates_ = refused;
    update_lost_ = true;
    spdlog::warn("{}: an update was refused on receipt: a gap until the next snapshot",
                 dds::topics::kMapUpdate.info.name);
  }
  takeFleetPaths();
  // In lockstep an operator's goal takes effect a fixed delay after its stamp, not when it
  // happens to arrive: the replans that follow it, and so the runs, repeat.
  while (auto g = goal_.take()) {
    counters().samples_in++;
    if (lockstep()) {
      goals_due_.hold(dds::topics::operatorInputDueNs(g->header().stamp_ns(), simClock().ns()), std::move(*g));
    } else {
      takeGoal(*g);
    }
  }
  takeStates();
  takeMapSamples();
  // Each state in its order, with the map due by its time: in lockstep the clock runs on
  // while a replan works, up to the path's budget, and the states meanwhile wait here.
  while (!held_states_.empty() && handleState(held_states_.front())) {
    held_states_.pop_front();
  }
  reportLockstep();
}

runtime::ModuleEntry planningModule() { return runtime::moduleEntry<PlanningNode>("planning", planningNodeSchema(), planningConfigFrom); }

}  // namespace quad::planning
