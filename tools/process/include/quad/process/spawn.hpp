// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A program started in its own process group, with its standard output and error on one
/// pipe: what the launcher supervises and what multi-process tests drive. It gets SIGTERM
/// when its parent dies, however that happens.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace quad::process {

class Spawned {
public:
  /// Starts `argv[0]` (a path, or a name looked up on PATH) with `env` added to this
  /// process's environment. Throws std::runtime_error when the pipe or fork fails; a
  /// program that cannot be executed exits with status 127.
  Spawned(std::vector<std::string> argv, const std::map<std::string, std::string>& env = {});
  ~Spawned();  // SIGKILLs the process group and reaps the child if it still runs
  Spawned(const Spawned&) = delete;
  Spawned& operator=(const Spawned&) = delete;

  pid_t pid() const { return pid_; }
  /// The read end of the output pipe (non-blocking), for poll(2).
  int outputFd() const { return out_fd_; }

  /// Appends what the child wrote and is pending to `out`; false once the pipe is closed.
  bool readOutput(std::string& out);

  /// The exit status once the child ended: its code, or 128 + the signal that ended it.
  /// Does not block.
  std::optional<int> poll();

  /// Sends `signal` to the child's process group.
  void signal(int signal) const;

  /// The CPU time the child took, user and system, all its threads [s]; known once poll()
  /// gave its exit status.
  std::optional<double> cpuSeconds() const { return cpu_s_; }
  /// The most memory the child held resident at once [MiB] (its rusage's maximum resident
  /// set size); known once poll() gave its exit status.
  std::optional<double> maxResidentMiB() const { return max_rss_mib_; }
  /// The times the child's threads waited (common::waits); known once poll() gave its exit status.
  std::optional<std::uint64_t> waits() const { return waits_; }

private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  std::optional<int> status_;
  std::optional<double> cpu_s_;
  std::optional<double> max_rss_mib_;
  std::optional<std::uint64_t> waits_;
};

/// Describes an exit status as poll() gives it: "exit 0", "killed by SIGKILL".
std::string describeStatus(int status);

}  // namespace quad::process
