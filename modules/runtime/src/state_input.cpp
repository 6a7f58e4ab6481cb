// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/state_input.hpp"

#include "quad/common/time.hpp"

#include "quad/dds/geometry_messages.hpp"
#include "quad/dds/sim_period_filter.hpp"

namespace quad::runtime {

std::vector<std::pair<std::string, StateSource>> stateSourceNames()
{
  return {{"estimate", StateSource::kEstimate}, {"truth", StateSource::kTruth}};
}

const char* toString(StateSource s) { return s == StateSource::kTruth ? "truth" : "estimate"; }

const dds::TopicInfo& stateTopic(StateSource s)
{
  return s == StateSource::kTruth ? dds::topics::kSimState.info : dds::topics::kEstimatedState.info;
}

std::int64_t statePeriodNs(double rate_hz)
{
  return rate_hz > 0.0 ? common::toNanoseconds(1.0 / rate_hz) : 0;
}

StateInput::StateInput(dds::Participant& participant, StateSource source, dds::Waker* waker, std::int32_t depth,
                       std::int64_t period_ns)
    : source_(source)
{
  const auto qos = readerQosWith(participant, stateTopic(source), depth, period_ns);
  if (source == StateSource::kTruth) {
    truth_.emplace(participant, dds::topics::kSimState, waker, qos);
  } else {
    estimate_.emplace(participant, dds::topics::kEstimatedState, waker, qos);
  }
}

namespace {
/// The fields both state messages have.
template <typename Message>
StateSample sampleOf(const Message& m)
{
  StateSample s;
  s.stamp_ns = m.header().stamp_ns();
  s.seq = m.header().seq();
  s.p_W = dds::toVector(m.p_W());
  s.v_W = dds::toVector(m.v_W());
  s.q_WB = dds::toQuaternion(m.q_WB());
  s.w_B = dds::toVector(m.w_B());
  return s;
}
}  // namespace

std::vector<StateSample> StateInput::takeAll()
{
  std::vector<StateSample> out;
  if (truth_) {
    for (const auto& m : truth_->takeAll()) {
      out.push_back(sampleOf(m));
      out.back().landed = m.landed();
    }
    return out;
  }
  for (const auto& m : estimate_->takeAll()) {
    out.push_back(sampleOf(m));
    out.back().aligned = m.aligned();
    out.back().covariance_ok = m.covariance_ok();
    out.back().accel_bias_B = dds::toVector(m.accel_bias_B());
    out.back().gyro_bias_B = dds::toVector(m.gyro_bias_B());
  }
  return out;
}

}  // namespace quad::runtime
