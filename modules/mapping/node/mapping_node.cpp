// SPDX-License-Identifier: BSD-3-Clause
#include "mapping_node.hpp"

#include "quad/common/layout.hpp"
#include "quad/world/world_file.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"
#include "quad/geometry/cspace.hpp"
#include "quad/mapping/checkpoint.hpp"

namespace quad::mapping {

namespace {
constexpr std::size_t kMaxChangesPerMessage = 262144;  // MapUpdate's bound
constexpr std::uint64_t kSeqReserve = 1'000'000;  // update numbers a checkpoint reserves ahead
constexpr std::int32_t kHeldClouds = 32;   // 3.2 s of the camera's 10 Hz: beyond the largest budget
// A cloud between two states read is placed on the pose interpolated between them, which
// PoseHistory does over at most 100 ms: two periods (the first state of a period can come late
// in it) within that.
constexpr double kMinStateRate = 20.0;

msg::VoxelState toMessage(VoxelState s)
{
  switch (s) {
    case VoxelState::kFree:
      return msg::VOXEL_FREE;
    case VoxelState::kOccupied:
      return msg::VOXEL_OCCUPIED;
    default:
      return msg::VOXEL_UNKNOWN;
  }
}
}  // namespace

const common::ParamTable<MappingParams>& mappingTable()
{
  using P = MappingParams;
  static const common::ParamTable<P> table = [] {
    common::ParamTable<P> t;
    t.include(mapperTable(), [](P& p) -> MapperParams& { return p.mapper; })
        .path("world", [](P& p) -> std::filesystem::path& { return p.world_file; },
              "world file whose box the map covers (one voxel beyond); empty: unbounded")
        .list("frames", [](P& p) -> std::set<std::string>& { return p.frames; }, "comma-separated sensor frames accepted")
        .number("snapshot.period", [](P& p) -> double& { return p.snapshot_period_s; }, {0.05, 3600.0}, "s",
                "sim time between map snapshots")
        .text("save_path", [](P& p) -> std::string& { return p.save_path; }, {},
              ".bt file written on shutdown and on COMMAND_SAVE_MAP; empty: never")
        .text("checkpoint.file", [](P& p) -> std::string& { return p.checkpoint_file; }, {},
              "the map resumed from at the start and written with every snapshot; empty: none");
    runtime::declareStateSource(t, [](P& p) -> runtime::StateSource& { return p.state_source; });
    runtime::declareStateRate(t, [](P& p) -> double& { return p.state_rate; },
                              "; at least " + common::formatValue(kMinStateRate) +
                                  ": a cloud is placed on the pose interpolated between the states around it");
    return t;
  }();
  return table;
}

common::ParamSchema mappingSchema() { return mappingTable().schema(); }

MappingNodeConfig mappingConfigFrom(const common::Params& p)
{
  const MappingParams m = mappingTable().read(p, common::configDir());
  MappingNodeConfig c;
  c.map = mapperConfigFrom(m.mapper, p.origin());
  if (!m.world_file.empty()) {
    const world::Bounds b = world::loadWorld(m.world_file).bounds();
    c.map.coverWorld(b.min, b.max);
  }
  c.frames = m.frames;
  c.snapshot_period_s = m.snapshot_period_s;
  c.save_path = m.save_path;
  c.checkpoint_file = m.checkpoint_file;
  c.state_source = m.state_source;
  if (m.state_rate > 0.0 && m.state_rate < kMinStateRate) {
    throw common::ConfigError({common::configProblem(p.origin(), "state.rate", m.state_rate,
                                                     "below " + common::formatValue(kMinStateRate) +
                                                         " Hz: clouds between its states could not be placed "
                                                         "(0 reads every state)")});
  }
  c.state_period_ns = runtime::statePeriodNs(m.state_rate);
  return c;
}

MappingNode::MappingNode(MappingNodeConfig config, dds::Participant handle)
    : Node("mapping", std::move(handle)),
      config_(std::move(config)),
      mapper_(config_.map),
      // In lockstep the clock runs on while a cloud is integrated, up to the map update's
      // budget: the clouds and the states that come meanwhile wait here, none replaced by a
      // newer one (the next cloud is placed with the state of its own time).
      depth_(participant(), dds::topics::kSimDepth, waker(),
             dds::readerQosWith(participant(), dds::topics::kSimDepth.info, kHeldClouds)),
      state_(participant(), config_.state_source, waker(), runtime::kHeldStates, statePeriodNs()),
      commands_(participant(), dds::topics::kVehicleCommand, waker()),
      updates_(participant(), dds::topics::kMapUpdate),
      snapshots_(participant(), dds::topics::kMapSnapshot),
      stats_(participant(), dds::topics::kMapStats),
      lockstep_(participant(), runtime::kMapperParticipant),
      intake_(config_.frames)
{
  followSimClock(runtime::kHeldStates);  // a sample at the state's rate, each saying whether a state went out
  spdlog::info("mapping: resolution {} m, max range {} m, clouds placed on the {} ({})", config_.map.resolution,
               config_.map.max_range, runtime::toString(config_.state_source), state_.topic().name);
  const TreeImage empty = mapper_.image(false);  // the empty map's; resume() counts a resumed one
  map_bytes_ = empty.memory_bytes;
  map_nodes_ = empty.nodes;
  resume();
}

std::int64_t MappingNode::statePeriodNs()
{
  // In lockstep a cloud's update is due its budget after the cloud, and it can be made only once
  // a state at or after the cloud's time came: up to a period later. A budget shorter than the
  // period (0: the clock waits at every cloud) needs every state.
  const std::int64_t budget = participant().options().mapBudgetNs();
  if (config_.state_period_ns > budget) {
    spdlog::info("mapping: every state read: the map's budget ({} ms) is shorter than the state period ({} ms)",
                 budget / 1'000'000, config_.state_period_ns / 1'000'000);
    return 0;
  }
  return config_.state_period_ns;
}

void MappingNode::resume()
{
  if (config_.checkpoint_file.empty()) {
    return;
  }
  const auto meta = readCheckpoint(config_.checkpoint_file, mapper_);
  if (!meta) {
    spdlog::info("mapping: no checkpoint at {} yet: starting with an empty map", config_.checkpoint_file.string());
    return;
  }
  // Numbers from the reservation on: above every one the mapper before us published.
  update_seq_ = meta->next_update_seq - 1;
  reserved_seq_ = meta->next_update_seq;
  last_stamp_ns_ = meta->stamp_ns;
  // The resumed map at once, latched: a consumer holding the map from before fills the gap
  // the new numbering opens with it.
  const TreeImage image = mapper_.image(false);
  spdlog::info("mapping: resumed from {}: {} nodes, scans up to t = {:.3f} s, updates numbered from {}",
               config_.checkpoint_file.string(), image.nodes, common::toSeconds(meta->stamp_ns),
               meta->next_update_seq);
  map_bytes_ = image.memory_bytes;
  map_nodes_ = image.nodes;
  publishSnapshot(meta->stamp_ns, update_seq_, image.binary);
}

void MappingNode::publishSnapshot(std::int64_t stamp_ns, std::uint64_t update_seq, const std::vector<std::uint8_t>& bytes)
{
  if (bytes.size() > 4194304) {
    spdlog::warn("mapping: snapshot of {} bytes exceeds the 4 MiB a MapSnapshot carries; not sent", bytes.size());
    return;
  }
  msg::MapSnapshot snapshot;
  snapshot.header().stamp_ns(stamp_ns);
  snapshot.update_seq(update_seq);
  snapshot.resolution(mapper_.resolution());
  snapshot.octree(bytes);
  snapshots_.write(snapshot);
}

void MappingNode::checkpoint(std::int64_t stamp_ns, std::uint64_t floor, const std::vector<std::uint8_t>* tree_data)
{
  if (config_.checkpoint_file.empty()) {
    return;
  }
  try {
    if (tree_data != nullptr) {
      writeCheckpoint(config_.checkpoint_file, mapper_.resolution(), *tree_data, {floor, stamp_ns});
    } else {
      writeCheckpoint(config_.checkpoint_file, mapper_, {floor, stamp_ns});
    }
    reserved_seq_ = floor;
  } catch (const std::exception& e) {
    counters().errors++;
    spdlog::error("mapping: {}", e.what());
  }
}

void MappingNode::takeStates()
{
  for (const auto& s : state_.takeAll()) {
    counters().samples_in++;
    const double n = s.q_WB.norm();
    if (simClock().seen() && !simClock().vouchesFor(s.stamp_ns)) {
      // Taken, it would make every state after it look out of order.
      counters().errors++;
      spdlog::warn("{}: sample seq {} rejected: stamped {:.3f} s, ahead of the sim clock ({:.3f} s)",
                   state_.topic().name, s.seq, common::toSeconds(s.stamp_ns), common::toSeconds(simClock().ns()));
      continue;
    }
    states_heard_ns_ = std::max(states_heard_ns_, s.stamp_ns);
    if (!s.aligned || s.stamp_ns == poses_.newestNs()) {
      continue;  // an estimator still aligning (no pose yet), or a state answered again
    }
    if (!s.p_W.allFinite() || !s.v_W.allFinite() || !std::isfinite(n) || std::abs(n - 1.0) > 1e-3 ||
        !poses_.add(s.stamp_ns, {s.p_W, s.q_WB.normalized()}, s.v_W)) {
      counters().errors++;
      spdlog::warn("{}: sample seq {} rejected: not finite, not a unit attitude, or out of order", state_.topic().name,
                   s.seq);
    }
  }
}

void MappingNode::integratePending()
{
  // A cloud with no pose at its time when it goes fell in a gap of the states (or came while
  // the estimator was still aligning): refused, naming the state missing.
  pending_.release(
      {lockstep(), states_heard_ns_, simClock().ns()}, [this](std::int64_t stamp) { return poses_.at(stamp).has_value(); },
      [this](std::int64_t stamp) { return simClock().stateSentAt(stamp); },
      [this](const msg::PointCloud& cloud) {
        const std::int64_t stamp = cloud.header().stamp_ns();
        const auto body = poses_.at(stamp);
        takeOwedSnapshot();  // the map as the cloud before this one left it
        integrate(cloud, body,
                  body ? std::string() : fmt::format("no {} at its time ({:.3f} s)", state_.topic().name,
                                                     common::toSeconds(stamp)));
      });
}

void MappingNode::integrate(const msg::PointCloud& cloud, const std::optional<geometry::Pose3>& body_W,
                            const std::string& why)
{
  counters().samples_in++;
  frames_taken_ = cloud.frame() != 0 ? std::max(frames_taken_, cloud.frame()) : frames_taken_ + 1;
  DepthFrame frame{cloud.frame_id().to_string(), {}, dds::toVector(cloud.sensor_p_B()),
                   dds::toQuaternion(cloud.sensor_q_BS()), cloud.max_range()};
  frame.points_S.reserve(cloud.points().size());
  for (const msg::Point3f& p : cloud.points()) {
    frame.points_S.push_back({p.x(), p.y(), p.z()});
  }
  const auto scan = intake_.take(frame, body_W, why);
  const std::int64_t start = common::steadyTimeNs();
  const IntegrationResult result = std::holds_alternative<Scan>(scan)
                                       ? mapper_.integrate(std::get<Scan>(scan))
                                       : IntegrationResult{false, std::get<std::string>(scan), {}, 0};
  const double insert_s = common::toSeconds(common::steadyTimeNs() - start);
  if (!result.accepted) {
    ++rejected_;
    counters().errors++;
    spdlog::warn("{}: cloud seq {} rejected: {}",
                 dds::topics::kSimDepth.info.name, cloud.header().seq(), result.rejection);
    // Still one (empty) update below: consumers count clouds through them.
  }
  last_stamp_ns_ = cloud.header().stamp_ns();
  taken_stamp_ns_ = last_stamp_ns_;
  // Out when it is due (in lockstep the clock waits at that time for what is not): an
  // overrun when the clock got there first, meanwhile or before.
  const std::int64_t due_ns = last_stamp_ns_ + participant().options().mapBudgetNs();
  if (overran(due_ns, fmt::format("the update for depth frame {}", frames_taken_))) {
    ++overruns_;
  }
  // The change set, in as many messages as its bound needs, each with its own number.
  const std::uint64_t first_seq = update_seq_ + 1;
  const std::uint64_t messages = std::max<std::size_t>(1, (result.changes.size() + kMaxChangesPerMessage - 1) /
                                                              kMaxChangesPerMessage);
  if (!config_.checkpoint_file.empty() && update_seq_ + messages >= reserved_seq_) {
    // A mapper started after us resumes numbering at the reservation: renew it first (after
    // the checkpoint of a snapshot still being worked out, which keeps the reservation before).
    finishSnapshot(true);
    checkpoint(last_stamp_ns_, update_seq_ + messages + kSeqReserve);
  }
  for (std::size_t begin = 0; begin == 0 || begin < result.changes.size(); begin += kMaxChangesPerMessage) {
    msg::MapUpdate update;
    update.header().stamp_ns(due_ns);
    update.update_seq(++update_seq_);
    update.resolution(mapper_.resolution());
    update.depth_frames(frames_taken_);
    update.depth_stamp_ns(last_stamp_ns_);
    const std::size_t end = std::min(result.changes.size(), begin + kMaxChangesPerMessage);
    update.changes().reserve(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
      msg::VoxelChange c;
      c.ix(result.changes[i].index.x());
      c.iy(result.changes[i].index.y());
      c.iz(result.changes[i].index.z());
      c.state(toMessage(result.changes[i].state));
      update.changes().push_back(c);
    }
    if (!updates_.write(update)) {
      counters().errors++;
    }
    counters().samples_out++;
  }
  // The update is out: in lockstep the clock may go on. The octree catches up with the scans
  // when it is next read, for a snapshot (Mapper::settle): once for all the scans since.
  reportLockstep();
  // The stats count the map's nodes and bytes as the period's snapshot found them, from the
  // kFiguresLagScans-th scan after it on: its walk, on a thread of its own, need not end
  // before the next scans' stats, and the figures are the same whatever that thread took.
  if (snapshot_job_ && frames_taken_ >= snapshot_job_->frames + kFiguresLagScans) {
    finishSnapshot(true);
  }
  if (figures_ && frames_taken_ >= figures_->from_frames) {
    map_nodes_ = figures_->nodes;
    map_bytes_ = figures_->bytes;
    figures_.reset();
  }
  msg::MapStats stats;
  stats.header().stamp_ns(due_ns);
  stats.update_seq(first_seq);
  stats.points(static_cast<std::uint32_t>(result.points));
  stats.changed_voxels(static_cast<std::uint32_t>(result.changes.size()));
  stats.insert_time_s(insert_s);
  stats.map_nodes(map_nodes_);
  stats.map_bytes(map_bytes_);
  stats.rejected_clouds(rejected_);
  stats.skipped_clouds(skipped_);
  stats.overruns(overruns_);
  stats_.write(stats);
  if (match_pending_) {
    match_pending_ = false;
    match_until_ns_ = cloud.header().stamp_ns() + common::toNanoseconds(config_.snapshot_period_s);
  }
  // The periodic snapshots keep their sim-time schedule whatever readers join (the extra
  // ones for a reader that joined depend on when it did).
  const bool periodic = cloud.header().stamp_ns() >= next_snapshot_ns_;
  if (cloud.header().stamp_ns() <= match_until_ns_ || periodic) {
    if (periodic) {
      next_snapshot_ns_ = cloud.header().stamp_ns() + common::toNanoseconds(config_.snapshot_period_s);
    }
    owed_snapshot_ = OwedSnapshot{due_ns, last_stamp_ns_, periodic};
  }
}

void MappingNode::takeOwedSnapshot()
{
  if (!owed_snapshot_) {
    return;
  }
  finishSnapshot(true);  // one at a time, in order
  const OwedSnapshot owed = *owed_snapshot_;
  owed_snapshot_.reset();
  // One walk of the tree for the snapshot, the checkpoint and the memory use: a walk costs
  // the cache misses of reaching every node.
  dds::Waker* waker = this->waker();
  snapshot_job_ = SnapshotJob{mapper_.imageLater(!config_.checkpoint_file.empty(), [waker] { waker->notify(); }), owed,
                              update_seq_, reserved_seq_, frames_taken_};
}

void MappingNode::finishSnapshot(bool wait)
{
  if (!snapshot_job_ ||
      (!wait && snapshot_job_->image.wait_for(std::chrono::seconds(0)) != std::future_status::ready)) {
    return;
  }
  const SnapshotJob job = std::move(*snapshot_job_);
  snapshot_job_.reset();
  const TreeImage& image = job.image.get();
  if (job.owed.periodic) {
    figures_ = Figures{job.frames + kFiguresLagScans, image.nodes, image.memory_bytes};  // the period's snapshots only
  }
  publishSnapshot(job.owed.due_ns, job.update_seq, image.binary);
  checkpoint(job.owed.stamp_ns, job.reserved_seq, &image.data);
}

void MappingNode::onEvent(const dds::EndpointEvent& event)
{
  // A new reader of updates (a restarted planner, say) gets those published from its match
  // on, and the latched snapshot, up to a snapshot period old (its snapshot reader may even
  // match seconds earlier): the updates in between are lost to it, a gap it would wait out
  // until the next snapshot. A snapshot with every cloud for one snapshot period fills it at
  // once: the reader's side of the match can complete several updates after ours (half a
  // second, 5 clouds, on a loaded machine), and it then misses those too. A reader later
  // than the window still has the periodic snapshot within a period.
  if (event.kind == dds::EventKind::kMatched && event.topic == dds::topics::kMapUpdate.info.name) {
    match_pending_ = true;
  }
  Node::onEvent(event);
}

void MappingNode::reportLockstep()
{
  if (!lockstep() || !simClock().seen()) {
    return;
  }
  // Done up to just before the due time of the oldest depth frame not yet dealt with: one
  // waiting here, else one published and not yet here (stamped after the last taken), else
  // the next to come (stamped after the clock's time, whose frames are all taken).
  const std::int64_t oldest = !pending_.empty()                           ? pending_.oldestStampNs()
                              : frames_taken_ < simClock().depthFrames() ? taken_stamp_ns_ + 1
                                                                          : simClock().ns() + 1;
  const std::int64_t done = oldest + participant().options().mapBudgetNs() - 1;
  if (done < simClock().ns()) {
    lockstep_.holding(simClock().ns(), [this] {
      return fmt::format("{} of {} depth frames integrated", frames_taken_, simClock().depthFrames());
    });
  }
  // A frame dealt with is reported at once: a plant that counts the frames it wrote
  // (LockstepBarrier::inputGiven) then needs no report from us until the next one's due time.
  // Between frames the report is renewed as the clock nears it, for a clock owner that does not
  // count them (a replay).
  if (frames_taken_ > frames_reported_ && done > lockstep_.reportedNs()) {
    if (lockstep_.reportDone(done)) {
      frames_reported_ = frames_taken_;
    }
    return;
  }
  lockstep_.reportAhead(done, simClock().ns(), participant().options().mapBudgetNs());
}

void MappingNode::save()
{
  if (config_.save_path.empty()) {
    return;
  }
  if (mapper_.save(config_.save_path)) {
    spdlog::info("mapping: map saved to {}", config_.save_path.string());
  } else {
    spdlog::error("mapping: cannot write {}", config_.save_path.string());
  }
}

void MappingNode::onWake()
{
  while (auto c = commands_.take()) {
    if (c->kind() == msg::COMMAND_SAVE_MAP) {
      save();
    }
  }
  takeStates();
  // A cloud resent by a lockstep plant waiting for us is one we have, one waiting for its
  // state, or one taken just before it (its copies queue while we work): known by its frame.
  std::uint64_t have = pending_.empty() ? frames_taken_ : std::max(frames_taken_, pending_.newest().frame());
  for (auto& cloud : depth_.takeAll()) {
    if (cloud.frame() != 0 && cloud.frame() <= have) {
      continue;
    }
    have = std::max(have, cloud.frame());
    const std::int64_t stamp = cloud.header().stamp_ns();
    pending_.hold(stamp, std::move(cloud));
  }
  if (!lockstep()) {
    // Behind in real time: the newest cloud carries the freshest view; count the others
    // (integrate() then accounts for every frame up to the newest's number, those the
    // reader's history dropped while we were behind included).
    if (const std::size_t dropped = pending_.keepNewest(); dropped > 0) {
      skipped_ += dropped;
      spdlog::debug("mapping: skipped {} older clouds", dropped);
    }
  }
  integratePending();
  reportLockstep();
  takeOwedSnapshot();
  finishSnapshot(false);
}

void MappingNode::onStop()
{
  takeOwedSnapshot();
  finishSnapshot(true);
  save();
  // The node data for the checkpoint, from the blocks the last snapshot's image left as they were.
  const TreeImage image = mapper_.imageLater(!config_.checkpoint_file.empty()).get();
  checkpoint(last_stamp_ns_, std::max(reserved_seq_, update_seq_ + 1), &image.data);
  spdlog::info("mapping: {} updates, {} clouds rejected, {} skipped, map {} nodes, {} voxel updates skipped at a "
               "clamping bound",
               update_seq_, rejected_, skipped_, image.nodes, mapper_.updatesSkippedAtBounds());
}

runtime::ModuleEntry mappingModule() { return runtime::moduleEntry<MappingNode>("mapping", mappingSchema(), mappingConfigFrom); }

}  // namespace quad::mapping
