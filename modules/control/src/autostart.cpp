// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/autostart.hpp"

namespace quad::control {

std::optional<Command> Autostart::next(Mode mode)
{
  if (done_ || airborne(mode)) {
    done_ = true;
    return std::nullopt;
  }
  switch (mode) {
    case Mode::kDisarmed:
      return Command::kArm;
    case Mode::kIdle:
      return Command::kTakeoff;
    default:
      return std::nullopt;
  }
}

bool Autostart::newRefusal(const std::string& why)
{
  const bool fresh = why != last_refusal_;
  last_refusal_ = why;
  return fresh;
}

}  // namespace quad::control
