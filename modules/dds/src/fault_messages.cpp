// SPDX-License-Identifier: BSD-3-Clause
#include "quad/dds/fault_messages.hpp"

namespace quad::dds {

namespace {
struct KindPair {
  msg::FaultKind message;
  wire::DatagramFaultKind core;
};
constexpr KindPair kKinds[] = {
    {msg::FAULT_DATAGRAM_LOSS, wire::DatagramFaultKind::kLoss},
    {msg::FAULT_DATAGRAM_DELAY, wire::DatagramFaultKind::kDelay},
    {msg::FAULT_DATAGRAM_DUPLICATE, wire::DatagramFaultKind::kDuplicate},
    {msg::FAULT_DATAGRAM_REORDER, wire::DatagramFaultKind::kReorder},
    {msg::FAULT_DATAGRAM_CORRUPT, wire::DatagramFaultKind::kCorrupt},
};
}  // namespace

bool isDatagramFault(msg::FaultKind kind)
{
  for (const auto& k : kKinds) {
    if (k.message == kind) {
      return true;
    }
  }
  return false;
}

msg::FaultCommand toCommand(const wire::DatagramFault& fault, const std::string& module)
{
  msg::FaultCommand c;
  c.fault_id(fault.id);
  c.module_name(module);
  for (const auto& k : kKinds) {
    if (k.core == fault.kind) {
      c.kind(k.message);
    }
  }
  c.target(fault.from);
  c.index(-1);
  c.magnitude(fault.magnitude);
  c.duration_s(0.0);
  c.seed(static_cast<std::uint32_t>(fault.seed));
  return c;
}

std::optional<wire::DatagramFault> datagramFaultFrom(const msg::FaultCommand& command, std::string& why_not)
{
  wire::DatagramFault f;
  bool known = false;
  for (const auto& k : kKinds) {
    if (k.message == command.kind()) {
      f.kind = k.core;
      known = true;
    }
  }
  if (!known) {
    why_not = "not a datagram fault";
    return std::nullopt;
  }
  if (command.duration_s() > 0.0) {
    why_not = "a datagram fault lasts until cleared (duration_s must be <= 0)";
    return std::nullopt;
  }
  f.id = command.fault_id();
  f.magnitude = command.magnitude();
  f.from = command.target();
  f.seed = command.seed();
  why_not = f.invalidReason();
  if (!why_not.empty()) {
    return std::nullopt;
  }
  return f;
}

}  // namespace quad::dds
