// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/lockstep_ledger.hpp"

#include <cstdio>
#include <stdexcept>

#include "quad/common/time.hpp"

namespace quad::runtime {

LockstepLedger::LockstepLedger(std::vector<std::string> participants)
    : order_(std::move(participants))
{
  for (const auto& name : order_) {
    if (name.empty() || !done_.emplace(name, std::nullopt).second) {
      throw std::invalid_argument("lockstep participants: '" + name +
                                  "': names must be non-empty and unique");
    }
  }
}

LockstepLedger::Report LockstepLedger::report(std::string_view participant, std::int64_t done_ns)
{
  const auto it = done_.find(participant);
  if (it == done_.end()) {
    return Report::kUnknownParticipant;
  }
  if (it->second && done_ns < *it->second) {
    return Report::kWentBackwards;
  }
  it->second = done_ns;
  return Report::kAccepted;
}

bool LockstepLedger::caughtUp(std::int64_t sim_ns) const
{
  for (const auto& [name, done] : done_) {
    if (!done || *done < sim_ns) {
      return false;
    }
  }
  return true;
}

std::vector<std::string> LockstepLedger::lateNames(std::int64_t sim_ns) const
{
  std::vector<std::string> out;
  for (const auto& name : order_) {
    const auto& done = done_.find(name)->second;
    if (!done || *done < sim_ns) {
      out.push_back(name);
    }
  }
  return out;
}

std::vector<std::string> LockstepLedger::late(std::int64_t sim_ns) const
{
  std::vector<std::string> out = lateNames(sim_ns);
  for (std::string& name : out) {
    const auto& done = done_.find(name)->second;
    if (!done) {
      name += " (no report yet)";
    } else {
      char text[64];
      std::snprintf(text, sizeof(text), " (done up to %.3f s)", common::toSeconds(*done));
      name += text;
    }
  }
  return out;
}

std::optional<std::int64_t> LockstepLedger::doneNs(std::string_view participant) const
{
  const auto it = done_.find(participant);
  return it == done_.end() ? std::nullopt : it->second;
}

std::optional<std::int64_t> LockstepLedger::minimumDoneNs() const
{
  std::optional<std::int64_t> minimum;
  for (const auto& [name, done] : done_) {
    if (!done) {
      return std::nullopt;
    }
    if (!minimum || *done < *minimum) {
      minimum = done;
    }
  }
  return minimum;
}

}  // namespace quad::runtime
