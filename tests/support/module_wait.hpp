// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Waiting on a module the way the stack itself tells of it: its heartbeat on
/// quad/system/heartbeat (state, counters), or its reader of a topic as discovery sees it. For
/// tests that start nodes themselves.

#include <chrono>
#include <cstdint>
#include <string>

namespace quad::test {

/// Joins `domain` (UDP) and waits up to `timeout` for a heartbeat of `module` (its
/// module_name) in state MODULE_RUNNING; false if none came.
bool waitForRunningModule(int domain, const std::string& module, std::chrono::milliseconds timeout);

/// Joins `domain` (UDP) and waits up to `timeout` for a heartbeat of `module` counting at
/// least `errors` rejected inputs or failed writes; false if none came.
bool waitForModuleErrors(int domain, const std::string& module, std::uint64_t errors, std::chrono::milliseconds timeout);

/// Joins `domain` (UDP) and waits up to `timeout` until discovery sees a reader of `topic`
/// (another process's); false if none came.
bool waitForReader(int domain, const std::string& topic, std::chrono::milliseconds timeout);

}  // namespace quad::test
