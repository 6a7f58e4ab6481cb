// SPDX-License-Identifier: BSD-3-Clause
#include "start_gate.hpp"

#include <nlohmann/json.hpp>

#include "quad/dds/topics.hpp"
#include "quad/runtime/lockstep.hpp"
#include "quad/topic/samples.hpp"

namespace quad::record {

StartGate::StartGate(dds::Participant& participant) : reports_(participant, dds::topics::kLockstep.info) {}

void StartGate::clockSeen(std::uint32_t vehicle, std::int64_t sim_ns)
{
  if (!released_.contains(vehicle)) {
    waiting_.insert(vehicle);
    clock_ns_ = sim_ns;
  }
}

void StartGate::release(bool plant_matched)
{
  if (!plant_matched) {
    return;
  }
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const nlohmann::ordered_json report{{"participant", runtime::kRecorderParticipant}, {"done_ns", runtime::kDoneForGoodNs}};
    dds::RawSample raw = topic::encodeSample(dds::topics::kLockstep.info, report, clock_ns_, ++seq_, *it);
    if (!reports_.write(raw)) {
      ++it;  // tried again with the next clock sample
      continue;
    }
    released_.insert(*it);
    it = waiting_.erase(it);
  }
}

}  // namespace quad::record
