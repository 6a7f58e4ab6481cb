// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/sim_clock.hpp"

#include <algorithm>

#include "quad/dds/topics.hpp"

namespace quad::dds {

SimClockFollower::SimClockFollower(Participant& participant, Waker* waker, std::vector<std::uint32_t> served)
    : clock_(participant, topics::kSimClock, waker), served_(std::move(served))
{
}

bool SimClockFollower::update()
{
  bool arrived = false;
  while (const auto c = served_.empty() ? clock_.take() : clock_.takeServed(served_)) {
    arrived = true;
    seen_ = true;
    lockstep_ = c->lockstep();
    ns_ = std::max(ns_, c->sim_ns());
    depth_frames_ = std::max(depth_frames_, c->depth_frames());
    state_sent_ = c->state_sent();
  }
  return arrived;
}

bool SimClockFollower::vouchesFor(std::int64_t stamp_ns) const
{
  return stamp_ns <= ns_ + topics::kStateAheadOfClockNs;
}

}  // namespace quad::dds
