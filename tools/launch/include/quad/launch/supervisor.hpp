// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Runs a run's processes: starts them in their own process groups, prefixes every line
/// they print with their name on the console and keeps it in <log dir>/<name>.log, reports
/// their exits, and stops them (SIGTERM, then SIGKILL after a grace period).

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quad/process/spawn.hpp"

namespace quad::launch {

class Supervisor {
public:
  /// `console`: where the launcher's lines go, and the modules' output when `echo`.
  Supervisor(std::filesystem::path log_dir, std::FILE* console, bool echo);
  // Destroying it kills what still runs (each process::Spawned does).

  /// Starts `argv` as `name` (replacing an exited process of that name).
  void start(const std::string& name, const std::vector<std::string>& argv,
             const std::map<std::string, std::string>& env);

  bool running(const std::string& name) const;
  std::optional<pid_t> pid(const std::string& name) const;

  struct Exit {
    std::string name;
    int status = 0;  ///< as process::Spawned::poll gives it
  };
  /// Forwards output for up to `timeout_ms` (returns sooner when something exited) and
  /// returns the processes that exited since the last call.
  std::vector<Exit> pump(int timeout_ms);

  /// Sends `signal` to a running process's group; false if it is not running.
  bool signal(const std::string& name, int signal);

  /// SIGTERM, then SIGKILL if it has not exited after `grace_s`; returns its exit status
  /// (nothing if it was not running).
  std::optional<int> stop(const std::string& name, double grace_s);

  /// The CPU time [s] that the processes started as `name` took, summed over those that
  /// ended (a restarted module's instances together); nothing while none has ended.
  std::optional<double> cpuSeconds(const std::string& name) const;
  /// The most memory [MiB] any of those processes held resident at once; nothing while none
  /// has ended.
  std::optional<double> maxResidentMiB(const std::string& name) const;
  /// The times those processes' threads waited (common::waits), summed over those that
  /// ended; nothing while none has ended.
  std::optional<std::uint64_t> waits(const std::string& name) const;

  /// A line of the launcher's own, on the console and in launch.log.
  void say(const std::string& line);

  const std::filesystem::path& logDir() const { return log_dir_; }

private:
  struct Child {
    std::unique_ptr<process::Spawned> process;
    std::ofstream log;
    std::string partial;  // output after the last newline
    bool eof = false;     // its output pipe closed (it is exiting, or closed it)
    bool exited = false;
    std::optional<double> cpu_s;  // of the instances that ended
    std::optional<double> max_rss_mib;  // the most any of them held resident
    std::optional<std::uint64_t> waits;  // of the instances that ended
  };
  /// Bookkeeping for a child whose exit status came: marks it exited, counts its CPU time.
  static void ended(Child& child);
  void forward(const std::string& name, Child& child, bool flush_partial);

  std::filesystem::path log_dir_;
  std::FILE* console_;
  bool echo_;
  std::ofstream launch_log_;
  std::map<std::string, Child> children_;
  std::size_t width_ = 8;
};

/// glibc's allocator tunables (glibc's own variable, read when a process starts).
inline constexpr const char* kGlibcTunables = "GLIBC_TUNABLES";
/// The tunables a module starts with: those `given` (the manifest's environment's, else the
/// launcher's), with glibc's allocator asking for transparent huge pages for its heap and
/// large blocks (granted where the system grants them on request, as in the common "madvise"
/// mode) unless they say otherwise. The modules' large tables (a map's voxels, a planner's
/// tables, big samples' payloads) are then faulted in 2 MB at a time instead of 4 KB.
std::string moduleTunables(const std::string& given);

}  // namespace quad::launch
