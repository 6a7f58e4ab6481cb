// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A program run to its end, its output collected: the launcher's network set-up and the
/// security tool's openssl calls.

#include <string>
#include <vector>

namespace quad::process {

struct RunResult {
  int status = 0;      ///< as Spawned::poll gives it
  std::string output;  ///< standard output and error
};

/// Runs a command (argv, no shell) to its end.
RunResult run(const std::vector<std::string>& argv);

/// Same; throws std::runtime_error with the command and its output when it fails.
void runChecked(const std::vector<std::string>& argv);

}  // namespace quad::process
