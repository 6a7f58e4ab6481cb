// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// quad's DDS Security identities and their permissions, derived from the topic contracts.

#include <vector>

#include "quad/security/init.hpp"

namespace quad::security {

/// Every identity of quad and what it may do, from the topic contracts' owners: a module
/// publishes the topics it owns (and every module's heartbeat, lockstep and fault
/// acknowledgements); the launcher what the operator owns and the fault tool's topics; the
/// fault tool's bad-input publisher, replay and `topic pub` any quad topic; the recorder and
/// the other topic tools nothing. Every identity reads every quad topic.
std::vector<Role> quadRoles();

}  // namespace quad::security
