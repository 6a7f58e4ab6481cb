// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// When the planner counts the mapper as lost, from its heartbeat's liveliness (which the
/// middleware judges in wall time: a 0.5 s lease) and the vehicle's clock.
///
/// In real time the two clocks run together, and a lapse counts at once. In lockstep the wall
/// lease lapses also where the machine is merely too loaded for the mapper to assert it in
/// time (eight vehicles on two cores: a module waits seconds for the CPU) while sim time hardly
/// moves, so there a lapse counts only once it has lasted `lockstep_grace_ns` of sim time. A
/// mapper among the plant's lockstep participants stops the clock while it is stopped or gone,
/// and the vehicle with it; one outside them is lost that long after its lease ran out.

#include <cstdint>
#include <optional>

namespace quad::planning {

class MapperLapse {
public:
  explicit MapperLapse(std::int64_t lockstep_grace_ns) : grace_ns_(lockstep_grace_ns) {}

  /// Whether the mapper counts as lost now: `heartbeat_lost`, its heartbeat's state now;
  /// `sim_ns`, the sim clock (non-decreasing).
  bool update(bool heartbeat_lost, std::int64_t sim_ns, bool lockstep)
  {
    if (!heartbeat_lost) {
      since_ns_.reset();
      return false;
    }
    if (!since_ns_) {
      since_ns_ = sim_ns;
    }
    return !lockstep || sim_ns - *since_ns_ >= grace_ns_;
  }

private:
  std::int64_t grace_ns_;
  std::optional<std::int64_t> since_ns_;  // sim time the current lapse was first seen
};

}  // namespace quad::planning
