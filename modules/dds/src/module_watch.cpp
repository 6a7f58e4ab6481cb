// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/module_watch.hpp"

#include <algorithm>
#include <utility>

namespace quad::dds {

ModuleWatch::ModuleWatch(Participant& participant, std::string module_name, Waker* waker)
    : heartbeats_(participant, topics::kHeartbeat, waker), module_(std::move(module_name))
{
}

ModuleWatch::State ModuleWatch::update()
{
  std::uint64_t writer = 0;
  while (const auto hb = heartbeats_.take(&writer)) {
    if (hb->module_name().to_string() == module_) {
      writers_[writer] = true;  // a sample is a sign of life (a restarted module's new writer)
    }
  }
  // Changes of writers not (yet) known as the module's are of other modules, or come before
  // their first heartbeat, which marks them alive anyway.
  for (const auto& change : heartbeats_.takeLivelinessChanges()) {
    const auto it = writers_.find(change.writer);
    if (it != writers_.end()) {
      it->second = change.alive;
    }
  }
  if (writers_.empty()) {
    return State::kUnknown;
  }
  return std::any_of(writers_.begin(), writers_.end(), [](const auto& w) { return w.second; }) ? State::kAlive
                                                                                                : State::kLost;
}

}  // namespace quad::dds
