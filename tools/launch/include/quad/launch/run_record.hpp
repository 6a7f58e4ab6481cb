// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A run's state for programs: `<run folder>/run.json`, rewritten whole (write, then rename)
/// at every change, so that a reader never sees half a file. It says how the hosts were set
/// up, which modules run where with which pid, how often each started and restarted, how each
/// last ended, whether the run failed and why, and the order modules were stopped in.
/// docs/launch.md describes it.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace quad::launch {

/// Where a module is in its life, as run.json spells it.
enum class ModulePhase {
  kWaiting,     ///< "waiting": not started yet (its needs have no writer yet, or an earlier one failed)
  kStarting,    ///< "starting": its process runs; no heartbeat of it yet
  kRunning,     ///< "running": its process runs and its heartbeat says MODULE_RUNNING
  kRestarting,  ///< "restarting": it exited and starts again after its back-off
  kExited,      ///< "exited": it exited and is not restarted (a normal end, or a fault meant it)
  kFailed,      ///< "failed": it exited with no restarts left; the run fails
  kStopped,     ///< "stopped": the launcher stopped it at the end of the run
};
std::string_view toString(ModulePhase phase);

/// "starting", "running", "stopping", "ended": the run's phase.
enum class RunPhase { kStarting, kRunning, kStopping, kEnded };
std::string_view toString(RunPhase phase);

struct ModuleRecord {
  std::string kind;  ///< the quad module it runs; "" for a program
  std::string host;
  ModulePhase phase = ModulePhase::kWaiting;
  int pid = 0;                  ///< of its newest start; 0 before the first
  int starts = 0;
  int restarts = 0;
  std::string last_exit;        ///< "exit 0", "killed by SIGKILL", ...; "" while it never ended
  std::int64_t started_ns = 0;  ///< wall time of its newest start [ns]
  /// Its command line (program, --config, --set, arguments), ${run_state} standing for the
  /// run's state folder: what `quad replay --inputs-of MODULE --compare` starts again.
  std::vector<std::string> command;
  /// A container's modules, by kind, each with the command line its own program would have
  /// had in the distributed layout: what a replay of one of them starts alone.
  std::map<std::string, std::vector<std::string>> hosted;
};

/// A host of the run as the launcher set it up.
struct HostRecord {
  std::string kind;               ///< "local", "netns", "ssh"
  std::string address;            ///< where the run's participants reach it
  std::string network_namespace;  ///< a netns host's namespace; "" otherwise
};

struct RunRecord {
  std::string manifest;
  std::string world;                       ///< the world file flown (absolute); "" when none
  int domain = 0;
  RunPhase phase = RunPhase::kStarting;
  std::string failure;                     ///< why the run failed; "" while nothing did
  std::optional<int> exit_code;            ///< once ended
  std::string discovery_server;            ///< "address:port" when the launcher runs one
  bool firewall = false;                   ///< the manifest's firewall rules are installed
  std::map<std::string, HostRecord> hosts;
  std::vector<std::string> order;          ///< the modules in the manifest's order
  std::map<std::string, ModuleRecord> modules;
  std::vector<std::string> stopped_order;  ///< modules in the order the launcher stopped them
};

/// The record as one JSON object.
std::string toJson(const RunRecord& record);

/// Writes `record` to `file` whole: to a temporary file beside it, then renamed over it.
/// False when it cannot be written.
bool writeRunRecord(const std::filesystem::path& file, const RunRecord& record);

}  // namespace quad::launch
