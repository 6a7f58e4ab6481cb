// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A node's side of its datagram fault layer: takes the faults quad/system/fault addresses
/// to the module, applies and clears them in the participant's DatagramFaults, and
/// acknowledges each on quad/system/fault_events.

#include <cstdint>
#include <string>

#include <quad/msg/FaultCommand.h>
#include <quad/msg/SimEvent.h>

#include "quad/dds/publisher.hpp"
#include "quad/dds/subscriber.hpp"
#include "quad/wire/datagram_faults.hpp"

namespace quad::runtime {

class FaultLayerControl {
public:
  /// `participant` must have a fault layer (ParticipantOptions::fault_layer).
  FaultLayerControl(dds::Participant& participant, std::string module_name, dds::Waker* waker);

  /// Handles every fault command that arrived.
  void take();

  /// The layer has (had) a fault with this id.
  bool knows(std::uint32_t id) const { return layer_.knows(id); }

  /// Logs what the faults still active did.
  void logActive() const;

private:
  void acknowledge(const msg::FaultCommand& command, msg::SimEventKind kind, const std::string& detail);

  wire::DatagramFaults& layer_;
  std::string module_name_;
  dds::Subscriber<msg::FaultCommand> commands_;
  dds::Publisher<msg::SimEvent> events_;
};

}  // namespace quad::runtime
