// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/count_guard.hpp"

#include <algorithm>

namespace quad::wire {

std::vector<CountGuard::Taming> CountGuard::admit(const std::vector<RtpsCount>& counts, std::int64_t now_ns)
{
  std::vector<Taming> out;
  if (counts.empty()) {
    return out;
  }
  std::lock_guard lock(mutex_);
  if (tracks_.size() > kMaxSenders) {
    tracks_.clear();  // a flood of forged senders: start over rather than grow
  }
  for (const RtpsCount& c : counts) {
    Track& t = tracks_[Key{c.kind, c.prefix, c.per_writer ? 0U : c.reader_id, c.writer_id}];
    const bool first = t.at_ns == 0;
    const double elapsed_s = first ? 0.0 : static_cast<double>(now_ns - t.at_ns) * 1e-9;
    const auto allowed = static_cast<std::uint64_t>(kSlack + kMaxRate * elapsed_s);
    const bool within = c.count <= t.highest || std::uint64_t{c.count} - t.highest <= allowed;
    const bool confirms = t.leap && c.count > *t.leap && c.count - *t.leap <= kSlack;
    t.at_ns = now_ns;
    if (within || confirms) {
      t.highest = std::max(t.highest, c.count);
      t.leap.reset();
      continue;
    }
    t.leap = c.count;
    ++t.highest;
    out.push_back({c, t.highest, first});
  }
  return out;
}

void CountGuard::apply(const std::vector<Taming>& tamings, std::uint8_t* datagram)
{
  for (const Taming& t : tamings) {
    std::uint8_t* p = datagram + t.count.count_offset;
    for (int i = 0; i < 4; ++i) {
      const int shift = t.count.little_endian ? 8 * i : 8 * (3 - i);
      p[i] = static_cast<std::uint8_t>(t.replaced >> shift);
    }
  }
}

}  // namespace quad::wire
