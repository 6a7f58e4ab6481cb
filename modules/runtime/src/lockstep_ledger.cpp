// SPDX-License-Identifier: BSD-3-Clause
#include "quad/runtime/lockstep_ledger.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "quad/common/time.hpp"

namespace quad::runtime {

LockstepLedger::LockstepLedger(std::vector<std::string> participants)
    : order_(std::move(participants))
{
  for (const auto& name : order_) {
    if (name.empty() || !entries_.emplace(name, Entry{}).second) {
      throw std::invalid_argument("lockstep participants: '" + name +
                                  "': names must be non-empty and unique");
    }
  }
}

LockstepLedger::Report LockstepLedger::report(std::string_view participant, std::int64_t done_ns)
{
  const auto it = entries_.find(participant);
  if (it == entries_.end()) {
    return Report::kUnknownParticipant;
  }
  Entry& e = it->second;
  if (e.done && done_ns < *e.done) {
    return Report::kWentBackwards;
  }
  e.done = done_ns;
  while (!e.outstanding.empty() && e.outstanding.front() <= done_ns) {
    e.outstanding.pop_front();
  }
  return Report::kAccepted;
}

bool LockstepLedger::worksOnInputsOnly(std::string_view participant)
{
  const auto it = entries_.find(participant);
  if (it == entries_.end()) {
    return false;
  }
  it->second.inputs_only = true;
  return true;
}

bool LockstepLedger::inputGiven(std::string_view participant, std::int64_t due_ns)
{
  const auto it = entries_.find(participant);
  if (it == entries_.end()) {
    return false;
  }
  Entry& e = it->second;
  if (e.inputs_only && !(e.done && due_ns <= *e.done)) {
    e.outstanding.insert(std::upper_bound(e.outstanding.begin(), e.outstanding.end(), due_ns), due_ns);
  }
  return true;
}

std::optional<std::int64_t> LockstepLedger::doneUpTo(const Entry& e)
{
  if (!e.done || !e.inputs_only) {
    return e.done;
  }
  // Every input due up to the report is done; the first one outstanding is the earliest work due.
  return e.outstanding.empty() ? std::numeric_limits<std::int64_t>::max()
                               : std::max(*e.done, e.outstanding.front() - 1);
}

bool LockstepLedger::caughtUp(std::int64_t sim_ns) const
{
  for (const auto& [name, e] : entries_) {
    const auto done = doneUpTo(e);
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
    const auto done = doneUpTo(entries_.find(name)->second);
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
    const auto done = doneUpTo(entries_.find(name)->second);
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
  const auto it = entries_.find(participant);
  return it == entries_.end() ? std::nullopt : it->second.done;
}

std::optional<std::int64_t> LockstepLedger::doneUpToNs(std::string_view participant) const
{
  const auto it = entries_.find(participant);
  return it == entries_.end() ? std::nullopt : doneUpTo(it->second);
}

std::optional<std::int64_t> LockstepLedger::minimumDoneNs() const
{
  std::optional<std::int64_t> minimum;
  for (const auto& [name, e] : entries_) {
    const auto done = doneUpTo(e);
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
