// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Child processes for multi-process tests: start with arguments and extra environment,
/// capture standard output and error, wait with a timeout, kill what is left.

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

#include "quad/process/spawn.hpp"

namespace quad::test {

class ChildProcess {
public:
  /// Starts `argv[0]` (a path) with `env` added to this process's environment.
  ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env = {});
  // The destructor SIGKILLs the child's process group and reaps the child.
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Exit status, or nothing if it did not exit within `timeout` (the child keeps running).
  std::optional<int> wait(std::chrono::milliseconds timeout);
  /// Sends `signal` to the child's process group.
  void signal(int signal);
  pid_t pid() const { return child_.pid(); }

  /// Everything the child wrote to stdout and stderr so far (reads what is pending).
  const std::string& output();
  /// Waits until the output contains `text`; false after `timeout`.
  bool waitForOutput(const std::string& text, std::chrono::milliseconds timeout);

private:
  void readAvailable(int timeout_ms);
  process::Spawned child_;
  std::string output_;
};

}  // namespace quad::test
