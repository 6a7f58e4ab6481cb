// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The plant's defence against bad rotor commands: a command is never integrated unless it
/// is finite, in range (clamped and counted when not) and fresh. When commands are missing,
/// late or rejected, the last good command is held and the event counted.
///
/// A held command is not held whole for long: its differential part is a torque chosen for
/// the attitude of its moment, and flown open loop it spins the vehicle up (a held roll
/// correction of 1.5 N m turns an x500 over in 0.3 s). Past `failsafe_ns` without a fresh
/// command the guard stands in for the output board's failsafe (PX4IO's failsafe outputs act
/// when the flight computer falls silent): every rotor runs at the speed that gives the held
/// command's total thrust, so the vehicle keeps its lift with no torque until a controller
/// speaks again.

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
    std::uint64_t failsafe_steps = 0;  ///< steps integrated on the balanced failsafe command
  };

  /// `timeout_ns`: a command older than this (in sim time) is late, and holding one past it
  /// counts as stale. `failsafe_ns`: a held command older than this is flown balanced.
  CommandGuard(const vehicle::VehicleParams& vehicle, std::int64_t timeout_ns, std::int64_t failsafe_ns);

  /// Offers a command stamped `stamp_ns` at sim time `now_ns`.
  Verdict submit(const RotorArray& speeds, bool armed, std::int64_t stamp_ns, std::int64_t now_ns);

  /// The command to integrate at `now_ns`: the last good one (zero speeds while disarmed or
  /// before any), balanced once older than the failsafe age. Counts a stale step when the
  /// held command is older than the timeout.
  RotorArray command(std::int64_t now_ns);

  bool stale(std::int64_t now_ns) const;
  const Counters& counters() const { return counters_; }

private:
  double min_;
  double max_;
  std::int64_t timeout_ns_;
  std::int64_t failsafe_ns_;
  RotorArray held_{};
  RotorArray balanced_{};  ///< every rotor at the speed giving held_'s total thrust
  bool armed_ = false;
  bool have_command_ = false;
  std::int64_t held_stamp_ns_ = 0;
  Counters counters_;
};

}  // namespace quad::plant
