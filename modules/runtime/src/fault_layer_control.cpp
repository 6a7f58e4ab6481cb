// SPDX-License-Identifier: BSD-3-Clause
#include "fault_layer_control.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "quad/dds/fault_messages.hpp"
#include "quad/dds/topics.hpp"

namespace quad::runtime {

FaultLayerControl::FaultLayerControl(dds::Participant& participant, std::string module_name, dds::Waker* waker)
    : layer_(*participant.datagramFaults()),
      module_name_(std::move(module_name)),
      commands_(participant, dds::topics::kFault, waker),
      events_(participant, dds::topics::kFaultEvents)
{
  spdlog::info("datagram fault layer in front of UDP (shared memory and data-sharing off)");
}

void FaultLayerControl::take()
{
  while (const auto command = commands_.take()) {
    if (command->module_name().to_string() != module_name_) {
      continue;
    }
    if (command->kind() == msg::FAULT_CLEAR) {
      if (const auto tally = layer_.clear(command->fault_id())) {
        const std::string what = fmt::format("datagram fault {} cleared: it acted on {} of {} datagrams",
                                             command->fault_id(), tally->acted, tally->affected);
        spdlog::warn("{}", what);
        acknowledge(*command, msg::SIM_EVENT_FAULT_CLEARED, what);
      }
      continue;  // not the layer's: the module's own (the plant's) to clear
    }
    if (!dds::isDatagramFault(command->kind())) {
      continue;
    }
    std::string why_not;
    const auto fault = dds::datagramFaultFrom(*command, why_not);
    if (fault && !layer_.apply(*fault)) {
      why_not = "fault id " + std::to_string(fault->id) + " already in use";
    }
    if (!why_not.empty()) {
      spdlog::warn("{}: fault {} rejected: {}", dds::topics::kFault.info.name, command->fault_id(), why_not);
      acknowledge(*command, msg::SIM_EVENT_FAULT_REJECTED,
                  "fault " + std::to_string(command->fault_id()) + " rejected: " + why_not);
      continue;
    }
    spdlog::warn("datagram fault {} applied: {}", fault->id, fault->describe());
    acknowledge(*command, msg::SIM_EVENT_FAULT_APPLIED, fault->describe());
  }
}

void FaultLayerControl::logActive() const
{
  for (const auto& [id, tally] : layer_.tallies()) {
    spdlog::warn("datagram fault {} still active at exit: it acted on {} of {} datagrams", id, tally.acted,
                 tally.affected);
  }
}

void FaultLayerControl::acknowledge(const msg::FaultCommand& command, msg::SimEventKind kind,
                                    const std::string& detail)
{
  msg::SimEvent e;
  e.header().stamp_ns(command.header().stamp_ns());  // the command's sim time: nodes do not keep one
  e.kind(kind);
  e.subject_id(command.fault_id());
  e.detail((module_name_ + ": " + detail).substr(0, 256));
  events_.write(e);
}

}  // namespace quad::runtime
