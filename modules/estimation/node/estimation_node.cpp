// SPDX-License-Identifier: BSD-3-Clause
#include "estimation_node.hpp"

#include <algorithm>
#include <variant>
#include <vector>

#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"

namespace quad::estimation {

namespace {
/// [ns] Wall time a lockstep estimator waits for an aid its IMU sample says was written before
/// it; one that has not come by then was lost (a best-effort datagram), and is not waited for.
constexpr std::int64_t kAidGraceNs = 200'000'000;

std::uint64_t seqOf(const EstimationNode::Sample& s)
{
  return std::visit([](const auto& m) { return m.header().seq(); }, s);
}
}  // namespace

EstimationNode::EstimationNode(EstimatorParams params, dds::Participant handle)
    : Node("estimation", std::move(handle)),
      filter_(params),
      imu_(participant(), dds::topics::kSimImu, waker()),
      position_(participant(), dds::topics::kSimPosition, waker()),
      baro_(participant(), dds::topics::kSimBaro, waker()),
      mag_(participant(), dds::topics::kSimMag, waker()),
      state_(participant(), dds::topics::kEstimatedState),
      held_(kAidGraceNs)
{
  // The clock says whether the run is a lockstep one, where the wall clock's deadlines say
  // nothing. A run known to be one from the start (QUAD_LOCKSTEP) stays one: its clock sample
  // of every round would wake this process for nothing (each IMU sample paces it already).
  if (!lockstep()) {
    followSimClock();
  }
  setWakeOnReceipt(true);  // each IMU sample is filtered on the thread that received it
  spdlog::info("estimation: gates at probability {}, health bounds {} m and {} rad", params.gate_probability,
               params.max_position_std, params.max_attitude_std);
}

void EstimationNode::judge(Update u, const dds::TopicInfo& topic, std::uint64_t seq)
{
  counters().samples_in++;
  if (u == Update::kBadInput || u == Update::kTooOld) {
    counters().errors++;
    spdlog::debug("{}: sample seq {} refused: {}", topic.name, seq, toString(u));
  }
}

void EstimationNode::onWake()
{
  std::vector<Timed> samples;
  for (auto& m : position_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  for (auto& m : baro_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  for (auto& m : mag_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  if (!lockstep()) {
    for (auto& m : imu_.takeAll()) {
      samples.emplace_back(m.header().stamp_ns(), std::move(m));
    }
    process(std::move(samples));
    return;
  }
  // In lockstep each IMU sample is answered with exactly the aids the plant wrote before it
  // (its *_seq), whenever they arrive, so that runs repeat.
  for (auto& a : samples) {
    const std::size_t kind = a.second.index() - 1;
    const std::uint64_t seq = seqOf(a.second);
    held_.holdAid(kind, seq, std::move(a));
  }
  for (auto& m : imu_.takeAll()) {
    const Pairing::Numbers wanted{m.position_seq(), m.baro_seq(), m.mag_seq()};
    held_.holdTrigger(std::move(m), wanted);
  }
  answerHeldImu();
}

void EstimationNode::answerHeldImu()
{
  while (const msg::Imu* front = held_.front()) {
    const std::int64_t stamp = front->header().stamp_ns();
    if (held_.answeredAny() && stamp <= filter_.timeNs()) {
      // Sent again by a plant still waiting for the round: the answer it had.
      held_.dropFront();
      if (stamp == filter_.timeNs()) {
        answerAgain(stamp);
      } else {
        counters().samples_in++;  // older than the newest answer: answered long ago
      }
      continue;
    }
    // The first answer waits until every aid's writer matched: the aids written before it
    // (lost or not, depending on when this participant matched) are left out; every one
    // after it reaches a matched reader.
    const bool matched = held_.answeredAny() || (position_.matchedWriters() > 0 && baro_.matchedWriters() > 0 &&
                                                 mag_.matchedWriters() > 0);
    auto paired = held_.next(common::steadyTimeNs(), matched);
    if (!paired) {
      return;  // woken by the aid, or by the plant resending the IMU sample
    }
    counters().samples_in += paired->left_out;
    if (paired->lost) {
      const auto& w = paired->wanted;
      const auto& n = paired->newest;
      counters().errors++;
      spdlog::warn("estimation: the IMU sample at {:.3f} s follows aids that have not come within {} ms "
                   "(position {} barometer {} magnetometer {}, the newest taken {} {} {}): lost; answered without them",
                   common::toSeconds(stamp), kAidGraceNs / 1'000'000, w[0], w[1], w[2], n[0], n[1], n[2]);
    }
    std::vector<Timed> due = std::move(paired->aids);
    due.emplace_back(stamp, std::move(paired->trigger));
    process(std::move(due));
  }
}

void EstimationNode::process(std::vector<Timed> samples)
{
  // Every sample, in the order of its stamp: the aids between IMU samples land where they
  // belong (a fix stamped in the past is the filter's to place). At equal stamps the IMU
  // first, so an aid corrects the state of its own time.
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second.index() < b.second.index();
  });
  for (const auto& [stamp, sample] : samples) {
    if (const auto* m = std::get_if<msg::Imu>(&sample)) {
      // Every IMU sample is answered, aligned or not (a lockstep round waits for the answer);
      // one sent again (a lockstep plant resends while it waits) with the answer it had.
      if (stamp == filter_.timeNs()) {
        answerAgain(stamp);
        continue;
      }
      const Update u = filter_.imu(stamp, dds::toVector(m->specific_force_B()), dds::toVector(m->angular_rate_B()));
      judge(u, dds::topics::kSimImu.info, m->header().seq());
      if (u != Update::kBadInput && u != Update::kTooOld) {
        publish();
      }
    } else if (const auto* p = std::get_if<msg::PositionFix>(&sample)) {
      judge(filter_.position(stamp, dds::toVector(p->p_W()), p->std_dev()), dds::topics::kSimPosition.info,
            p->header().seq());
    } else if (const auto* b = std::get_if<msg::BaroAltitude>(&sample)) {
      judge(filter_.baro(stamp, b->altitude(), b->std_dev()), dds::topics::kSimBaro.info, b->header().seq());
    } else if (const auto* g = std::get_if<msg::MagneticField>(&sample)) {
      judge(filter_.mag(stamp, dds::toVector(g->field_B()), g->std_dev()), dds::topics::kSimMag.info,
            g->header().seq());
    }
  }
  if (filter_.aligned() && !announced_alignment_) {
    announced_alignment_ = true;
    const Estimate e = filter_.estimate(filter_.timeNs());
    spdlog::info("estimation: aligned at t = {:.3f} s, at ({:.2f}, {:.2f}, {:.2f})", common::toSeconds(e.t_ns),
                 e.p_W.x(), e.p_W.y(), e.p_W.z());
  }
}

void EstimationNode::answerAgain(std::int64_t stamp_ns)
{
  counters().samples_in++;
  if (last_ && last_->header().stamp_ns() == stamp_ns) {
    state_.write(*last_);
    counters().samples_out++;
  } else {
    publish();
  }
}

void EstimationNode::publish()
{
  // Health is judged at the state's own time: a stale IMU shows as the state's age, which
  // its readers judge by the contract's deadline.
  const Estimate e = filter_.estimate(filter_.timeNs());
  msg::EstimatedState m;
  m.header().stamp_ns(e.t_ns);
  m.p_W(dds::toMessage(e.p_W));
  m.v_W(dds::toMessage(e.v_W));
  m.q_WB(dds::toMessage(e.q_WB));
  m.w_B(dds::toMessage(e.w_B));
  m.a_W(dds::toMessage(e.a_W));
  m.accel_bias_B(dds::toMessage(e.accel_bias_B));
  m.gyro_bias_B(dds::toMessage(e.gyro_bias_B));
  m.baro_offset(e.baro_offset);
  m.p_std(dds::toMessage(e.p_std));
  m.v_std(dds::toMessage(e.v_std));
  m.attitude_std(dds::toMessage(e.attitude_std));
  m.aligned(e.health.aligned);
  m.imu_ok(e.health.imu_ok);
  m.position_aided(e.health.position_aided);
  m.heading_aided(e.health.heading_aided);
  m.covariance_ok(e.health.covariance_ok);
  m.position_rejected(filter_.positionCounts().rejected);
  m.baro_rejected(filter_.baroCounts().rejected);
  m.mag_rejected(filter_.magCounts().rejected);
  m.position_resets(filter_.positionResets());
  state_.write(m);
  last_ = m;
  counters().samples_out++;
}

runtime::ModuleEntry estimationModule() { return runtime::moduleEntry<EstimationNode>("estimation", estimatorSchema(), estimatorParamsOf); }

}  // namespace quad::estimation
