// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Participants side by side in one test process: each talks to the others over UDP on the
/// test's own domain, as separate processes would (for targets that link quad::dds).

#include "quad/dds/participant.hpp"

namespace quad::test {

/// The options of a participant named `name` on `domain`, after turning off the
/// middleware's delivery within the process (dds::intraprocessDeliveryOff: two participants
/// of one process must meet through the transport).
inline dds::ParticipantOptions sideBySide(const char* name, int domain)
{
  dds::intraprocessDeliveryOff();
  return dds::ParticipantOptions{.name = name, .domain_id = domain, .transport = dds::Transport::kUdp};
}

}  // namespace quad::test
