// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The estimation participant: feeds the plant's IMU, position fixes, barometer and
/// magnetometer to the error-state filter in time order and publishes its state after every
/// IMU sample.

#include <optional>

#include "quad/dds/node.hpp"
#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/dds/topics.hpp"
#include "quad/estimation/error_state_filter.hpp"

namespace quad::estimation {

class EstimationNode : public dds::Node {
public:
  EstimationNode(EstimatorParams params, dds::ParticipantOptions options);

protected:
  void onWake() override;

private:
  /// Counts a sample the filter refused as bad input (not a gate's refusal: that is the
  /// filter's own judgement, published in the state).
  void judge(Update u, const dds::TopicInfo& topic, std::uint64_t seq);
  void publish();

  ErrorStateFilter filter_;
  dds::Subscriber<msg::Imu> imu_;
  dds::Subscriber<msg::PositionFix> position_;
  dds::Subscriber<msg::BaroAltitude> baro_;
  dds::Subscriber<msg::MagneticField> mag_;
  dds::Publisher<msg::EstimatedState> state_;
  bool announced_alignment_ = false;
  std::optional<msg::EstimatedState> last_;  // the newest estimate published
  std::int64_t first_imu_ns_ = -1;           // the stamp of the first IMU sample taken
};

}  // namespace quad::estimation
