// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The estimation participant: feeds the plant's IMU, position fixes, barometer and
/// magnetometer to the error-state filter in time order and publishes its state after every
/// IMU sample.

#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/estimation/error_state_filter.hpp"
#include "quad/runtime/aid_pairing.hpp"
#include "quad/runtime/module_main.hpp"
#include "quad/runtime/node.hpp"

namespace quad::estimation {

class EstimationNode : public runtime::Node {
public:
  EstimationNode(EstimatorParams params, dds::Participant handle);

  /// The IMU first: its index orders samples of equal stamps; an aid's kind is its index - 1.
  using Sample = std::variant<msg::Imu, msg::PositionFix, msg::BaroAltitude, msg::MagneticField>;
  using Timed = std::pair<std::int64_t, Sample>;

protected:
  void onWake() override;

private:
  /// Counts a sample the filter refused as bad input (not a gate's refusal: that is the
  /// filter's own judgement, published in the state).
  void judge(Update u, const dds::TopicInfo& topic, std::uint64_t seq);
  void publish();
  /// An IMU sample sent again (a lockstep plant resends while it waits): the answer it had.
  void answerAgain(std::int64_t stamp_ns);
  /// Feeds samples to the filter in the order of their stamps, answering each IMU sample.
  void process(std::vector<Timed> samples);
  /// In lockstep: answers the IMU samples held whose aids have come (see the .cpp).
  void answerHeldImu();

  ErrorStateFilter filter_;
  dds::Subscriber<msg::Imu> imu_;
  dds::Subscriber<msg::PositionFix> position_;
  dds::Subscriber<msg::BaroAltitude> baro_;
  dds::Subscriber<msg::MagneticField> mag_;
  dds::Publisher<msg::EstimatedState> state_;
  bool announced_alignment_ = false;
  std::optional<msg::EstimatedState> last_;  // the newest estimate published
  // In lockstep: IMU samples not yet answered and the aids (position, barometer,
  // magnetometer) not yet fed, each answered with the aids written before it.
  using Pairing = runtime::AidPairing<msg::Imu, Timed, 3>;
  Pairing held_;
};

/// The estimation module as a process hosts it: its name, parameters and node.
runtime::ModuleEntry estimationModule();

}  // namespace quad::estimation
