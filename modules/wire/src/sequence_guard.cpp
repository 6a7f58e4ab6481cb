// SPDX-License-Identifier: BSD-3-Clause
#include "quad/wire/sequence_guard.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace quad::wire {

namespace {
constexpr std::uint8_t kGap = 0x08;
}  // namespace

std::optional<RtpsDefect> SequenceGuard::admit(const std::vector<RtpsSequence>& sequences, std::int64_t now_ns)
{
  if (sequences.empty()) {
    return std::nullopt;
  }
  std::lock_guard lock(mutex_);
  if (tracks_.size() > kMaxWriters) {
    tracks_.clear();  // a flood of forged writers: start over rather than grow
  }
  for (const RtpsSequence& s : sequences) {
    const auto found = tracks_.find(Key{s.prefix, s.writer_id});
    if (s.kind == kGap) {
      if (found == tracks_.end()) {
        continue;  // a writer not heard yet: nothing to judge by
      }
      const Track& t = found->second;
      const double elapsed_s = static_cast<double>(now_ns - t.at_ns) * 1e-9;
      const auto allowed = t.highest + kSlack + static_cast<std::int64_t>(kMaxRate * std::max(0.0, elapsed_s));
      if (s.last > allowed) {
        return RtpsDefect{s.offset, fmt::format("GAP from writer 0x{:08x}: sequence numbers up to {} irrelevant, "
                                                "{:.1f} s after the writer stated {}",
                                                s.writer_id, s.last, elapsed_s, t.highest)};
      }
      continue;
    }
    Track& t = found == tracks_.end() ? tracks_[Key{s.prefix, s.writer_id}] : found->second;
    const bool first = t.at_ns == 0;
    const double elapsed_s = first ? 0.0 : static_cast<double>(now_ns - t.at_ns) * 1e-9;
    const auto allowed = t.highest + kSlack + static_cast<std::int64_t>(kMaxRate * std::max(0.0, elapsed_s));
    const bool confirms = t.leap && s.last >= *t.leap - kSlack && s.last <= *t.leap + kSlack;
    if (first || s.last <= allowed || confirms) {
      t.highest = std::max(t.highest, s.last);
      t.at_ns = now_ns;
      t.leap.reset();
    } else {
      t.leap = s.last;
    }
  }
  return std::nullopt;
}

}  // namespace quad::wire
