// SPDX-License-Identifier: BSD-3-Clause
// A participant's options from the process's environment (the QUAD_* names of
// environment.hpp), each checked and refused with its name and value.
#include <arpa/inet.h>

#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fastrtps/utils/IPLocator.h>

#include "participant_inputs.hpp"
#include "quad/common/layout.hpp"
#include "quad/common/payload_header.hpp"
#include "quad/dds/environment.hpp"
#include "quad/dds/participant.hpp"
#include "quad/dds/topics.hpp"

namespace quad::dds {

namespace frtps = eprosima::fastrtps::rtps;

namespace {

constexpr std::uint32_t kMinUdpMessage = 1200;   // room for an RTPS header and a fragment
constexpr std::uint32_t kMaxUdpMessage = 65500;  // Fast DDS's own limit

const char* env(const char* name)
{
  const char* value = std::getenv(name);
  return (value != nullptr && *value != '\0') ? value : nullptr;
}

}  // namespace

frtps::Locator_t parseLocator(const std::string& text, std::string_view what, bool port_required)
{
  const auto colon = text.rfind(':');
  const std::string ip = text.substr(0, colon);
  in_addr addr{};
  if (inet_pton(AF_INET, ip.c_str(), &addr) != 1) {
    throw std::invalid_argument(std::string(what) + ": " + text + ": not an IPv4 address");
  }
  frtps::Locator_t locator;
  frtps::IPLocator::setIPv4(locator, ip);
  if (colon != std::string::npos) {
    locator.port = parseInt<std::uint32_t>(std::string_view(text).substr(colon + 1), what, 1, 65535);
  } else if (port_required) {
    throw std::invalid_argument(std::string(what) + ": " + text + ": expected IP:PORT");
  }
  return locator;
}

Transport parseTransport(std::string_view text)
{
  if (text == "default") {
    return Transport::kDefault;
  }
  if (text == "udp") {
    return Transport::kUdp;
  }
  if (text == "shm") {
    return Transport::kSharedMemory;
  }
  throw std::invalid_argument("transport: " + std::string(text) + ": expected default, udp or shm");
}

std::filesystem::path defaultQosFile()
{
  if (const char* file = env(environment::kQosFile)) {
    return file;
  }
  return common::configDir() / "dds" / "quad_qos.xml";
}

ParticipantOptions optionsFromEnvironment(std::string name)
{
  ParticipantOptions options;
  options.name = std::move(name);
  if (const char* v = env(environment::kDomainId)) {
    options.domain_id = parseInt<int>(v, environment::kDomainId, 0, kMaxDomainId);
  }
  if (const char* v = env(environment::kTransport)) {
    try {
      options.transport = parseTransport(v);
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument(std::string(environment::kTransport) + ": " + v +
                                  ": expected default, udp or shm");
    }
  }
  if (const char* v = env(environment::kInitialPeers)) {
    std::stringstream list(v);
    for (std::string peer; std::getline(list, peer, ',');) {
      if (!peer.empty()) {
        parseLocator(peer, environment::kInitialPeers, false);
        options.initial_peers.push_back(peer);
      }
    }
  }
  if (const char* v = env(environment::kInterfaces)) {
    std::stringstream list(v);
    for (std::string address; std::getline(list, address, ',');) {
      if (address.empty()) {
        continue;
      }
      if (address.find(':') != std::string::npos) {
        throw std::invalid_argument(std::string(environment::kInterfaces) + ": " + address +
                                    ": expected an IPv4 address, without a port");
      }
      parseLocator(address, environment::kInterfaces, false);
      options.interfaces.push_back(address);
    }
  }
  if (const char* v = env(environment::kDiscoveryServer)) {
    parseLocator(v, environment::kDiscoveryServer, true);
    options.discovery_server = v;
  }
  if (const char* v = env(environment::kVehicleId)) {
    options.vehicle_id = parseInt<std::uint32_t>(v, environment::kVehicleId, 0, common::kMaxVehicleId);
  }
  if (const char* v = env(environment::kUdpMaxMessage)) {
    options.udp_max_message = parseInt<std::uint32_t>(v, environment::kUdpMaxMessage, kMinUdpMessage, kMaxUdpMessage);
  }
  if (const char* v = env(environment::kFaultLayer)) {
    options.fault_layer = parseInt<int>(v, environment::kFaultLayer, 0, 1) == 1;
  }
  if (const char* v = env(environment::kSecurityDir)) {
    options.security_dir = v;
  }
  if (const char* v = env(environment::kSecurityIdentity)) {
    options.security_identity = v;
  }
  if (const char* v = env(environment::kValidateDatagrams)) {
    options.validate_datagrams = parseInt<int>(v, environment::kValidateDatagrams, 0, 1) == 1;
  }
  if (const char* v = env(environment::kInlineKeys)) {
    options.inline_keys = parseInt<int>(v, environment::kInlineKeys, 0, 1) == 1;
  }
  if (const char* v = env(environment::kLockstep)) {
    options.lockstep = parseInt<int>(v, environment::kLockstep, 0, 1) == 1;
  }
  if (const char* v = env(environment::kLockstepRecorder)) {
    options.lockstep_recorder = parseInt<int>(v, environment::kLockstepRecorder, 0, 1) == 1;
  }
  if (const char* v = env(environment::kLockstepObserver)) {
    options.lockstep_observer = parseInt<int>(v, environment::kLockstepObserver, 0, 1) == 1;
  }
  if (const char* v = env(environment::kParticipantLease)) {
    options.participant_lease_s = parseInt<int>(v, environment::kParticipantLease, 1, std::numeric_limits<int>::max());
  }
  if (const char* v = env(environment::kMapBudget)) {
    options.map_budget_ns = 1'000'000LL * parseInt<int>(v, environment::kMapBudget, 0, 1000);
  }
  if (const char* v = env(environment::kPathBudget)) {
    options.path_budget_ns = 1'000'000LL * parseInt<int>(v, environment::kPathBudget, 0, 1000);
  }
  options.qos_file = defaultQosFile();
  return options;
}

std::int64_t ParticipantOptions::mapBudgetNs() const { return map_budget_ns.value_or(topics::kMapUpdateBudgetNs); }

std::int64_t ParticipantOptions::pathBudgetNs() const { return path_budget_ns.value_or(topics::kPathBudgetNs); }

}  // namespace quad::dds
