// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/datagram_faults.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

namespace quad::wire {

namespace {
constexpr double kMaxDelayS = 10.0;
constexpr std::uint8_t kRtpsMagic[4] = {'R', 'T', 'P', 'S'};
}  // namespace

std::string toString(DatagramFaultKind kind)
{
  switch (kind) {
    case DatagramFaultKind::kLoss:
      return "loss";
    case DatagramFaultKind::kDelay:
      return "delay";
    case DatagramFaultKind::kDuplicate:
      return "duplicate";
    case DatagramFaultKind::kReorder:
      return "reorder";
    case DatagramFaultKind::kCorrupt:
      return "corrupt";
  }
  return "unknown";
}

std::string DatagramFault::invalidReason() const
{
  if (id == 0) {
    return "fault id 0 is invalid";
  }
  const bool delay = kind == DatagramFaultKind::kDelay;
  const double hi = delay ? kMaxDelayS : 1.0;
  if (!std::isfinite(magnitude) || magnitude < 0.0 || magnitude > hi) {
    return fmt::format("{} {}: expected {} in [0, {}]", toString(kind), magnitude,
                       delay ? "seconds" : "a probability", hi);
  }
  return "";
}

std::string DatagramFault::describe() const
{
  const std::string what = kind == DatagramFaultKind::kDelay
                               ? fmt::format("delay {} s of datagrams", magnitude)
                               : fmt::format("{} {} of datagrams", toString(kind), magnitude);
  return fmt::format("{} from {} (seed {})", what, from.empty() ? "every sender" : from, seed);
}

bool DatagramFaults::apply(const DatagramFault& fault)
{
  if (!fault.invalidReason().empty()) {
    return false;
  }
  // The kind joins the seed: one seed given to several kinds draws a sequence for each.
  std::seed_seq seq{static_cast<std::uint32_t>(fault.seed), static_cast<std::uint32_t>(fault.seed >> 32),
                    static_cast<std::uint32_t>(fault.kind)};
  std::lock_guard lock(mutex_);
  if (!active_.try_emplace(fault.id, Active{fault, std::mt19937_64(seq), {}}).second) {
    return false;
  }
  known_.insert(fault.id);
  return true;
}

std::optional<DatagramFaults::Tally> DatagramFaults::clear(std::uint32_t id)
{
  std::lock_guard lock(mutex_);
  const auto it = active_.find(id);
  if (it == active_.end()) {
    return std::nullopt;
  }
  const Tally t = it->second.tally;
  active_.erase(it);
  return t;
}

std::map<std::uint32_t, DatagramFaults::Tally> DatagramFaults::tallies() const
{
  std::lock_guard lock(mutex_);
  std::map<std::uint32_t, Tally> out;
  for (const auto& [id, a] : active_) {
    out[id] = a.tally;
  }
  return out;
}

bool DatagramFaults::knows(std::uint32_t id) const
{
  std::lock_guard lock(mutex_);
  return known_.count(id) > 0;
}

bool DatagramFaults::idle() const
{
  std::lock_guard lock(mutex_);
  return active_.empty();
}

void DatagramFaults::learnSender(const GuidPrefix& prefix, const std::string& name)
{
  std::lock_guard lock(mutex_);
  senders_[prefix] = name;
}

bool DatagramFaults::affects(const Active& a, const std::string* sender) const
{
  return a.fault.from.empty() || (sender != nullptr && *sender == a.fault.from);
}

DatagramFate DatagramFaults::fate(const std::uint8_t* datagram, std::size_t size)
{
  DatagramFate f;
  std::lock_guard lock(mutex_);
  ++counts_.seen;
  if (active_.empty()) {
    return f;
  }
  const std::string* sender = nullptr;
  if (size >= kRtpsHeaderSize && std::memcmp(datagram, kRtpsMagic, sizeof(kRtpsMagic)) == 0) {
    GuidPrefix prefix;
    std::copy_n(datagram + 8, prefix.size(), prefix.begin());
    if (const auto it = senders_.find(prefix); it != senders_.end()) {
      sender = &it->second;
    }
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  bool reordered = false;
  for (auto& [id, a] : active_) {
    if (!affects(a, sender)) {
      continue;
    }
    ++a.tally.affected;
    // Every fault draws once per datagram it affects, so one fault's decisions do not
    // depend on which others are active.
    const double draw = unit(a.rng);
    bool acted = false;
    switch (a.fault.kind) {
      case DatagramFaultKind::kLoss:
        acted = draw < a.fault.magnitude;
        f.drop = f.drop || acted;
        break;
      case DatagramFaultKind::kDelay:
        acted = a.fault.magnitude > 0.0;
        f.delay_ns += static_cast<std::int64_t>(a.fault.magnitude * 1e9);
        break;
      case DatagramFaultKind::kDuplicate:
        acted = draw < a.fault.magnitude;
        f.copies = acted ? 2 : f.copies;
        break;
      case DatagramFaultKind::kReorder:
        acted = draw < a.fault.magnitude;
        if (acted) {
          f.delay_ns += kReorderHoldNs;
          reordered = true;
        }
        break;
      case DatagramFaultKind::kCorrupt:
        // Past the RTPS header: a damaged header only makes the datagram unreadable (a
        // loss); damage behind it reaches the parsers.
        acted = draw < a.fault.magnitude && size > kRtpsHeaderSize;
        if (acted) {
          f.corrupt = kRtpsHeaderSize + static_cast<std::size_t>(a.rng() % (size - kRtpsHeaderSize));
          f.corrupt_bit = static_cast<int>(a.rng() % 8);
        }
        break;
    }
    a.tally.acted += acted ? 1U : 0U;
  }
  if (f.drop) {
    ++counts_.dropped;
    return DatagramFate{true};
  }
  counts_.reordered += reordered ? 1U : 0U;
  counts_.delayed += f.delay_ns > 0 ? 1U : 0U;
  counts_.duplicated += f.copies > 1 ? 1U : 0U;
  counts_.corrupted += f.corrupt ? 1U : 0U;
  return f;
}

DatagramFaults::Counts DatagramFaults::counts() const
{
  std::lock_guard lock(mutex_);
  return counts_;
}

}  // namespace quad::wire
