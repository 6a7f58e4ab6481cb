// SPDX-License-Identifier: BSD-3-Clause
#include "estimation_node.hpp"

#include <algorithm>
#include <variant>
#include <vector>

#include <spdlog/spdlog.h>

#include "quad/common/time.hpp"
#include "quad/dds/geometry_messages.hpp"

namespace quad::estimation {

EstimationNode::EstimationNode(EstimatorParams params, dds::ParticipantOptions options)
    : Node("estimation", std::move(options)),
      filter_(params),
      imu_(participant(), dds::topics::kSimImu, waker()),
      position_(participant(), dds::topics::kSimPosition, waker()),
      baro_(participant(), dds::topics::kSimBaro, waker()),
      mag_(participant(), dds::topics::kSimMag, waker()),
      state_(participant(), dds::topics::kEstimatedState)
{
  followSimClock();  // in lockstep the wall clock's deadlines say nothing
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
  // Every sample taken, in the order of its stamp: the aids between IMU samples land where
  // they belong (a fix stamped in the past is the filter's to place). At equal stamps the
  // IMU first, so an aid corrects the state of its own time.
  using Sample = std::variant<msg::Imu, msg::PositionFix, msg::BaroAltitude, msg::MagneticField>;
  std::vector<std::pair<std::int64_t, Sample>> samples;
  for (auto& m : imu_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  for (auto& m : position_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  for (auto& m : baro_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  for (auto& m : mag_.takeAll()) {
    samples.emplace_back(m.header().stamp_ns(), std::move(m));
  }
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second.index() < b.second.index();
  });
  for (const auto& [stamp, sample] : samples) {
    // Aids stamped before the first IMU sample taken are not used: whether they came depends
    // on when this participant matched the plant's writers, and a run would not repeat.
    if (sample.index() != 0 && (first_imu_ns_ < 0 || stamp < first_imu_ns_)) {
      counters().samples_in++;
      continue;
    }
    if (const auto* m = std::get_if<msg::Imu>(&sample)) {
      if (first_imu_ns_ < 0) {
        first_imu_ns_ = stamp;
      }
      // Every IMU sample is answered, aligned or not (a lockstep round waits for the answer);
      // one sent again (a lockstep plant resends while it waits) with the answer it had, even
      // if an aid came since.
      if (stamp == filter_.timeNs()) {
        counters().samples_in++;
        if (last_ && last_->header().stamp_ns() == stamp) {
          state_.write(*last_);
          counters().samples_out++;
        } else {
          publish();
        }
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

}  // namespace quad::estimation
