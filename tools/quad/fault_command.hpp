#pragma once
/// @file
/// `quad fault SCENARIO`: launches a scenario's manifest, applies its faults on its timeline,
/// checks the stack's reactions and the run's outcome, and prints a pass/fail table.

#include <optional>
#include <string>

namespace quad::tools {

struct FaultOptions {
  std::string scenario;
  std::optional<int> domain;          ///< replaces the manifest's and the environment's
  std::optional<std::string> log_dir; ///< the run's folder; default log/fault-<name>-<time>
  double wall_timeout_s = 0.0;        ///< stop and fail after this long; 0 = never
  bool quiet = false;                 ///< modules' output to their logs only
  bool check = false;                 ///< validate the scenario and its manifest, then exit
};

/// 0: every check passed; 1: some failed; 2: the scenario or its manifest is invalid.
int fault(const FaultOptions& options);

}  // namespace quad::tools
