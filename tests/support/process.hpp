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

namespace quad::test {

class ChildProcess {
public:
  /// Starts `argv[0]` (a path) with `env` added to this process's environment.
  ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env = {});
  ~ChildProcess();  // SIGKILLs the child's process group and reaps the child
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Exit status, or nothing if it did not exit within `timeout` (the child keeps running).
  std::optional<int> wait(std::chrono::milliseconds timeout);
  /// Sends `signal` to the child's process group.
  void signal(int signal);
  pid_t pid() const { return pid_; }

  /// Everything the child wrote to stdout and stderr so far (reads what is pending).
  const std::string& output();
  /// Waits until the output contains `text`; false after `timeout`.
  bool waitForOutput(const std::string& text, std::chrono::milliseconds timeout);

private:
  void readAvailable(int timeout_ms);
  pid_t pid_ = -1;
  int out_fd_ = -1;
  std::string output_;
  std::optional<int> status_;
};

}  // namespace quad::test
