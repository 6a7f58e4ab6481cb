// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/sim_clock.hpp"

#include <algorithm>
#include <iterator>

#include "quad/dds/sim_period_filter.hpp"
#include "quad/dds/topics.hpp"

namespace quad::runtime {

SimClockFollower::SimClockFollower(dds::Participant& participant, dds::Waker* waker, std::vector<std::uint32_t> served,
                                   std::int32_t depth)
    : SimClockFollower(participant, waker, std::move(served),
                       readerQosWith(participant, dds::topics::kSimClock.info, depth))
{
}

SimClockFollower::SimClockFollower(dds::Participant& participant, dds::Waker* waker, std::vector<std::uint32_t> served,
                                   std::optional<eprosima::fastdds::dds::DataReaderQos> qos)
    : clock_(participant, dds::topics::kSimClock, waker, std::move(qos)), served_(std::move(served))
{
}

SimClockFollower SimClockFollower::onlooker(dds::Participant& participant, std::vector<std::uint32_t> served,
                                            std::int64_t period_ns)
{
  auto qos = dds::withMinimumSeparation(participant.readerQos(dds::topics::kSimClock.info), period_ns);
  qos.reliability().kind = eprosima::fastdds::dds::BEST_EFFORT_RELIABILITY_QOS;
  return SimClockFollower(participant, nullptr, std::move(served), qos);
}

bool SimClockFollower::update()
{
  bool arrived = false;
  while (const auto c = served_.empty() ? clock_.take() : clock_.takeServed(served_)) {
    arrived = true;
    seen_ = true;
    lockstep_ = c->lockstep();
    ns_ = std::max(ns_, c->sim_ns());
    if (c->depth_frames() > depth_frames_) {
      depth_frames_ = c->depth_frames();
      frames_by_ns_.emplace_back(c->sim_ns(), depth_frames_);
    }
    if (!c->state_sent() && (unsent_ns_.empty() || unsent_ns_.back() < c->sim_ns())) {
      unsent_ns_.push_back(c->sim_ns());
    }
    if (c->state_sent()) {
      last_sent_ns_ = std::max(last_sent_ns_, c->sim_ns());
    }
    state_sent_ = c->state_sent();
  }
  // The count at any time within the history needs the newest entry at or before it.
  while (frames_by_ns_.size() > 1 && frames_by_ns_[1].first <= ns_ - kHistoryNs) {
    frames_by_ns_.pop_front();
  }
  while (!unsent_ns_.empty() && unsent_ns_.front() < ns_ - kHistoryNs) {
    unsent_ns_.pop_front();
  }
  return arrived;
}

bool SimClockFollower::stateSentAt(std::int64_t ns) const
{
  return !std::binary_search(unsent_ns_.begin(), unsent_ns_.end(), ns);
}

std::uint64_t SimClockFollower::depthFramesAt(std::int64_t ns) const
{
  const auto after = std::upper_bound(frames_by_ns_.begin(), frames_by_ns_.end(), ns,
                                      [](std::int64_t t, const auto& entry) { return t < entry.first; });
  return after == frames_by_ns_.begin() ? 0 : std::prev(after)->second;
}

bool SimClockFollower::vouchesFor(std::int64_t stamp_ns) const
{
  return stamp_ns <= ns_ + dds::topics::kStateAheadOfClockNs;
}

}  // namespace quad::runtime
