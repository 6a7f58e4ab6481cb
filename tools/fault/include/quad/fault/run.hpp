// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad fault`'s engine: loads a scenario, checks it against its manifest, launches the
/// manifest with the fault driver applying the steps on the scenario's timeline, and judges
/// the stack's reactions and the run's outcome.

#include <optional>
#include <string>

#include "quad/fault/scenario.hpp"

namespace quad::fault {

struct FaultOptions {
  std::string scenario;
  std::optional<int> domain;          ///< replaces the manifest's and the environment's
  std::optional<std::string> layout;  ///< distributed | composed; replaces the manifest's
  std::optional<std::string> log_dir; ///< the run's folder; default log/fault-<name>-<time>
  double wall_timeout_s = 0.0;        ///< stop and fail after this long; 0 = never
  bool quiet = false;                 ///< modules' output to their logs only
  bool no_report = false;             ///< no report.html at the end (the run always records: the checks read it)
  bool check = false;                 ///< validate the scenario and its manifest, then exit
};

/// 0: every check passed; 1: some failed; 2: the scenario or its manifest is invalid.
int runScenario(const FaultOptions& options);

/// What a scenario is checked against: the controller's mode names and the topics' IDL.
ScenarioLookup scenarioLookup();

}  // namespace quad::fault
