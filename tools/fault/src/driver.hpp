// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The fault driver: a RunExtension that applies a scenario's steps to a LaunchRun on its
/// timeline (processes, plant faults, datagram faults, link faults, bad inputs), watches the
/// stack's reactions through the launcher's participant and feeds them to the Judge.

#include <filesystem>
#include <memory>

#include "quad/fault/scenario.hpp"
#include "quad/launch/run.hpp"

namespace quad::fault {

/// `recording`: the run's MCAP file, which the driver audits at the end.
std::unique_ptr<launch::RunExtension> makeDriver(const Scenario& scenario, std::filesystem::path recording);

}  // namespace quad::fault
