// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The vehicle state a module flies on: the estimator's (quad/estimation/state), or, to
/// compare against it, the plant's ground truth (quad/sim/state). One reader, either topic,
/// one sample type, so control, planning and mapping switch with one parameter.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "quad/common/param_table.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/geometry/quaternion.hpp"

namespace quad::runtime {

enum class StateSource { kEstimate, kTruth };

/// "estimate", "truth": the names a config's `state.source` takes (common::ParamTable::choice).
std::vector<std::pair<std::string, StateSource>> stateSourceNames();
const char* toString(StateSource s);
/// The topic a source is read from.
const dds::TopicInfo& stateTopic(StateSource s);
/// [ns] The sim-time period of `rate_hz` states a second: StateInput's `period_ns`; 0 for 0.
std::int64_t statePeriodNs(double rate_hz);

/// Declares `state.source` in a module's parameter table: which state it flies on (or draws),
/// with the choices and meaning every module shares; `also` adds what it means for this module.
template <typename Config, typename Field>
void declareStateSource(common::ParamTable<Config>& table, Field field, std::string_view also = {})
{
  table.choice("state.source", field, stateSourceNames(),
               "the vehicle state flown on: the estimator's (quad/estimation/state), or the plant's ground truth "
               "(quad/sim/state) to compare against it" +
                   std::string(also));
}

/// Declares `state.rate` for a module that needs fewer states than the plant's steps
/// (StateInput's period: statePeriodNs()); `also` adds what it means for this module.
template <typename Config, typename Field>
void declareStateRate(common::ParamTable<Config>& table, Field field, std::string_view also = {})
{
  table.number("state.rate", field, {0.0, 1000.0}, "Hz",
               "states read per second of sim time, at most (the first of each period): their writers send no "
               "more; 0: every one" +
                   std::string(also));
}

/// One vehicle state, whichever the source.
struct StateSample {
  std::int64_t stamp_ns = 0;
  std::uint64_t seq = 0;
  /// The truth always; an estimate once the filter is aligned (before, nothing else holds).
  bool aligned = true;
  geometry::Vector3 p_W = geometry::Vector3::Zero();  ///< [m]
  geometry::Vector3 v_W = geometry::Vector3::Zero();  ///< [m/s]
  geometry::Quaternion q_WB;                          ///< body to world
  geometry::Vector3 w_B = geometry::Vector3::Zero();  ///< [rad/s]
  /// The plant's ground contact: the truth only. On an estimate the reader judges it.
  std::optional<bool> landed;
  /// The estimator's position and attitude 1-sigma within its bounds (its `health.max_*_std`);
  /// the truth always.
  bool covariance_ok = true;
  /// The estimator's IMU biases (zero for the truth): a reader that integrates the IMU itself
  /// (the controller's dead reckoning) takes them off.
  geometry::Vector3 accel_bias_B = geometry::Vector3::Zero();  ///< [m/s²]
  geometry::Vector3 gyro_bias_B = geometry::Vector3::Zero();   ///< [rad/s]
};

/// The unread states (and clock samples) kept by a reader that works while the lockstep clock
/// runs on up to its budget: 2 s at the contract's 250 Hz, beyond the largest budget (1 s).
inline constexpr std::int32_t kHeldStates = 512;

/// Reads the chosen source's topic.
class StateInput {
public:
  /// `depth` > 0: the reader keeps that many unread samples, not the topic profile's newest
  /// only (a reader that needs the state of a given time after working for a while).
  /// `period_ns` > 0: at most one sample per that much sim time (withMinimumSeparation).
  StateInput(dds::Participant& participant, StateSource source, dds::Waker* waker, std::int32_t depth = 0,
             std::int64_t period_ns = 0);

  /// Every unread sample, oldest first.
  std::vector<StateSample> takeAll();
  StateSource source() const { return source_; }
  const dds::TopicInfo& topic() const { return stateTopic(source_); }

private:
  StateSource source_;
  std::optional<dds::Subscriber<msg::VehicleState>> truth_;
  std::optional<dds::Subscriber<msg::EstimatedState>> estimate_;
};

}  // namespace quad::runtime
