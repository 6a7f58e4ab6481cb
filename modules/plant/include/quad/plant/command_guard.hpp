// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The plant's defence against bad rotor commands: a command is never integrated unless it
/// is finite, in range (clamped and counted when not) and fresh. When commands are missing,
/// late or rejected, the last good command is held and the event counted.

#include <cstdint>

#include "quad/plant/dynamics.hpp"

namespace quad::plant {

class CommandGuard {
public:
  enum class Verdict {
    kAccepted,
    kClamped,          ///< some speed was below the minimum or above the maximum: clamped
    kRejectedInvalid,  ///< a non-finite speed: ignored, last good command held
    kRejectedLate,     ///< stamped more than the timeout before now: ignored
    kRejectedOld,      ///< stamped before the command already held: ignored (reordered)
  };

  struct Counters {
    std::uint64_t accepted = 0;
    std::uint64_t clamped = 0;
    std::uint64_t rejected_invalid = 0;
    std::uint64_t rejected_late = 0;
    std::uint64_t rejected_old = 0;
    std::uint64_t stale_steps = 0;  ///< steps integrated on a held command older than the timeout
  };

  /// `timeout_ns`: a command older than this (in sim time) is late, and holding one past it
  /// counts as stale.
  CommandGuard(const vehicle::VehicleParams& vehicle, std::int64_t timeout_ns);

  /// Offers a command stamped `stamp_ns` at sim time `now_ns`.
  Verdict submit(const RotorArray& speeds, bool armed, std::int64_t stamp_ns, std::int64_t now_ns);

  /// The command to integrate at `now_ns`: the last good one (zero speeds while disarmed or
  /// before any). Counts a stale step when the held command is older than the timeout.
  RotorArray command(std::int64_t now_ns);

  bool stale(std::int64_t now_ns) const;
  const Counters& counters() const { return counters_; }

private:
  double min_;
  double max_;
  std::int64_t timeout_ns_;
  RotorArray held_{};
  bool armed_ = false;
  bool have_command_ = false;
  std::int64_t held_stamp_ns_ = 0;
  Counters counters_;
};

}  // namespace quad::plant
