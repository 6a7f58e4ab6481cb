// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad's DDS Security identities and their permissions, derived from the topic contracts.

#include <string>
#include <vector>

#include "quad/security/init.hpp"

namespace quad::security {

/// Every identity of quad and what it may do, from the topic contracts' owners: a module
/// publishes the topics it owns (and every module's heartbeat, lockstep and fault
/// acknowledgements); the launcher what the operator owns, the fault tool's topics and
/// lockstep reports (its observer's start hold); the fault tool's bad-input publisher, replay
/// and `topic pub` any quad topic; the recorder only lockstep reports (its start gate); the
/// other topic tools nothing. Every identity reads every quad topic.
std::vector<Role> quadRoles();

/// The identity of a container hosting `modules` (quad_container, one participant): named as
/// its participant is (common::containerName: "plant+estimation+control", in that order), it
/// publishes what any of its modules may and reads every quad topic. Throws
/// std::invalid_argument for a name that is not a module's, or one given twice.
Role containerRole(const std::vector<std::string>& modules);

}  // namespace quad::security
