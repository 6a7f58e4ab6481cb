// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A mission that starts by itself (the demo's, a campaign's): the controller arms, then takes
/// off, with no operator. It asks again every tick until its command takes (one refused while
/// the first state is not yet fresh is not lost), and is done once the vehicle is in the air,
/// taking off or taken over in flight, so that a later landing is final.

#include <optional>
#include <string>

#include "quad/control/modes.hpp"

namespace quad::control {

class Autostart {
public:
  /// `enabled` false: it never asks.
  explicit Autostart(bool enabled) : done_(!enabled) {}

  /// The command to give in `mode` this tick: ARM when disarmed, TAKEOFF when idle; none in
  /// other modes, and none ever again once a mode was airborne.
  std::optional<Command> next(Mode mode);

  /// Whether its command's refusal `why` differs from the last one: a reason is worth a line
  /// once, not every tick it asks again.
  bool newRefusal(const std::string& why);

  bool done() const { return done_; }

private:
  bool done_;
  std::string last_refusal_;
};

}  // namespace quad::control
