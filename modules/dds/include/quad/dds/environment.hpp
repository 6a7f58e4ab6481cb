// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The environment variables that configure a participant, declared once: the participant
/// reads them (optionsFromEnvironment, participant.hpp) and the launcher and the fault tool
/// write them for the modules they start. docs/dds.md says what each one takes.

namespace quad::dds::environment {

inline constexpr const char* kDomainId = "QUAD_DOMAIN_ID";
inline constexpr const char* kTransport = "QUAD_TRANSPORT";
inline constexpr const char* kInitialPeers = "QUAD_INITIAL_PEERS";
inline constexpr const char* kInterfaces = "QUAD_INTERFACES";
inline constexpr const char* kDiscoveryServer = "QUAD_DISCOVERY_SERVER";
inline constexpr const char* kQosFile = "QUAD_QOS_FILE";
inline constexpr const char* kVehicleId = "QUAD_VEHICLE_ID";
inline constexpr const char* kUdpMaxMessage = "QUAD_UDP_MAX_MESSAGE";
inline constexpr const char* kSecurityDir = "QUAD_SECURITY_DIR";
inline constexpr const char* kSecurityIdentity = "QUAD_SECURITY_IDENTITY";
inline constexpr const char* kValidateDatagrams = "QUAD_VALIDATE_DATAGRAMS";
inline constexpr const char* kInlineKeys = "QUAD_INLINE_KEYS";
inline constexpr const char* kFaultLayer = "QUAD_FAULT_LAYER";
inline constexpr const char* kLockstep = "QUAD_LOCKSTEP";
inline constexpr const char* kLockstepRecorder = "QUAD_LOCKSTEP_RECORDER";
inline constexpr const char* kLockstepObserver = "QUAD_LOCKSTEP_OBSERVER";
inline constexpr const char* kParticipantLease = "QUAD_PARTICIPANT_LEASE";
inline constexpr const char* kMapBudget = "QUAD_MAP_BUDGET_MS";
inline constexpr const char* kPathBudget = "QUAD_PATH_BUDGET_MS";

}  // namespace quad::dds::environment
