// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Inputs due with another input, by the numbers it carries (DESIGN.md §5). In lockstep an
/// estimator answers each IMU sample with exactly the aids the plant wrote before it, whenever
/// the aids arrive, so that runs repeat: the plant numbers the aids of each kind it writes (a
/// header's seq) and every IMU sample names the newest of each kind written before it. This
/// holds both and hands out an IMU sample with the aids due with it once all of them have
/// come. An aid lost on the way (a best-effort datagram) is waited for a grace of wall time,
/// then left out. No DDS.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

namespace quad::runtime {

/// `Trigger`: the input answered (the IMU sample); `Aid`: what is due with it, of `Kinds`
/// kinds numbered apart (position, barometer, magnetometer).
template <typename Trigger, typename Aid, std::size_t Kinds>
class AidPairing {
public:
  using Numbers = std::array<std::uint64_t, Kinds>;

  struct Paired {
    Trigger trigger;
    std::vector<Aid> aids;     ///< due with it, in the order they came
    std::size_t left_out = 0;  ///< aids written before the first answer, dropped now
    bool lost = false;         ///< answered without aids that had not come within the grace
    Numbers wanted{};          ///< the newest of each kind it asked for
    Numbers newest{};          ///< the newest of each kind held so far
  };

  /// [ns] of wall time a trigger waits for an aid it names before the aid counts as lost.
  explicit AidPairing(std::int64_t grace_ns) : grace_ns_(grace_ns) {}

  /// An aid of `kind` numbered `seq`.
  void holdAid(std::size_t kind, std::uint64_t seq, Aid aid)
  {
    newest_[kind] = std::max(newest_[kind], seq);
    aids_.push_back({kind, seq, std::move(aid)});
  }

  /// A trigger that is due with the aids numbered up to `wanted`, kind by kind.
  void holdTrigger(Trigger trigger, const Numbers& wanted) { triggers_.emplace_back(std::move(trigger), wanted); }

  /// The oldest trigger not yet handed out; null when none is held.
  const Trigger* front() const { return triggers_.empty() ? nullptr : &triggers_.front().first; }

  /// Drops the oldest trigger unanswered (a sample sent again, answered already).
  void dropFront() { triggers_.pop_front(); }

  bool answeredAny() const { return answered_any_; }

  /// The oldest trigger with the aids due with it, once each has come or once it waited
  /// `grace_ns` of wall time since the first call that found one missing (`steady_ns`: now);
  /// none while it waits. The first trigger also waits for `writers_matched` (every aid's
  /// writer is known to the reader); the aids it names are taken as written before the reader
  /// could have them, and left out, as are those numbered up to them later.
  std::optional<Paired> next(std::int64_t steady_ns, bool writers_matched)
  {
    if (triggers_.empty()) {
      return std::nullopt;
    }
    const Numbers wanted = triggers_.front().second;
    if (!answered_any_) {
      if (!writers_matched) {
        return std::nullopt;
      }
      first_ = wanted;
    }
    bool complete = true;
    for (std::size_t k = 0; k < Kinds; ++k) {
      complete = complete && (wanted[k] <= first_[k] || newest_[k] >= wanted[k]);
    }
    bool lost = false;
    if (!complete) {
      if (wait_since_ns_ == 0) {
        wait_since_ns_ = steady_ns;
      }
      if (steady_ns - wait_since_ns_ < grace_ns_) {
        return std::nullopt;
      }
      lost = true;
    }
    wait_since_ns_ = 0;
    Paired out{std::move(triggers_.front().first), {}, 0, lost, wanted, newest_};
    triggers_.pop_front();
    std::vector<Held> later;
    for (Held& a : aids_) {
      if (a.seq <= first_[a.kind]) {
        ++out.left_out;
      } else if (a.seq <= wanted[a.kind]) {
        out.aids.push_back(std::move(a.aid));
      } else {
        later.push_back(std::move(a));
      }
    }
    aids_ = std::move(later);
    answered_any_ = true;
    return out;
  }

private:
  struct Held {
    std::size_t kind;
    std::uint64_t seq;
    Aid aid;
  };
  std::int64_t grace_ns_;
  std::deque<std::pair<Trigger, Numbers>> triggers_;
  std::vector<Held> aids_;
  Numbers newest_{};
  Numbers first_{};  // what the first answer named: those and older are left out
  bool answered_any_ = false;
  std::int64_t wait_since_ns_ = 0;  // wall time the front trigger began waiting (0: it does not)
};

}  // namespace quad::runtime
