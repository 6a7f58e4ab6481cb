// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One run of a manifest: sets up its hosts, starts its modules in order (each once the
/// topics it needs have a writer), supervises them (respawn, failure), flies the mission with
/// the launcher's observer, and stops everything in reverse order. `quad launch` runs it as
/// it is; `quad fault` drives it through a RunExtension to break the stack on purpose.

#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "quad/launch/hosts.hpp"
#include "quad/launch/manifest.hpp"
#include "quad/launch/mission.hpp"
#include "quad/launch/observer.hpp"
#include "quad/launch/run_record.hpp"
#include "quad/launch/supervisor.hpp"
#include "quad/plan/known_map.hpp"

namespace quad::launch {

/// How to run a manifest: `quad launch`'s options, which `quad fault` and `quad campaign`
/// fill too.
struct LaunchOptions {
  std::string manifest;
  std::optional<std::string> world;    ///< replaces the manifest's world
  bool realtime = false;               ///< mode realtime instead of the manifest's
  bool lockstep = false;               ///< mode lockstep instead of the manifest's
  std::optional<std::string> state;    ///< ${state} (estimate | truth) instead of the manifest's
  std::optional<std::uint64_t> seed;   ///< ${seed} instead of the manifest's
  std::optional<std::uint32_t> vehicle;  ///< a fleet manifest: this vehicle alone
  std::optional<std::string> layout;   ///< distributed | composed instead of the manifest's
  std::optional<int> domain;           ///< replaces the manifest's and the environment's
  std::optional<std::string> subnet;   ///< replaces the manifest's netns subnet
  std::optional<common::Geofence> geofence;  ///< replaces the manifest's keep-in volume
  std::vector<std::string> sets;       ///< MODULE:KEY=VALUE, each a module's parameter (ModuleSet)
  std::optional<std::string> summary;  ///< JSON summary of the mission to this file
  std::optional<std::string> log_dir;  ///< the run's folder; default log/<name>-<time>
  std::optional<std::string> record;   ///< record every topic to this MCAP file; default <run folder>/recording.mcap
  bool no_record = false;              ///< record nothing (and so write no report)
  bool no_report = false;              ///< no report.html at the end (docs/report.md)
  double wall_timeout_s = 0.0;         ///< stop and fail after this long; 0 = never
  bool quiet = false;                  ///< modules' output to their logs only
  bool check = false;                  ///< validate the manifest and exit
};

class LaunchRun;

/// `quad launch`'s exit status (docs/launch.md): 0 when every module ran as it should and the
/// mission, if any, succeeded.
inline constexpr int kExitFailed = 1;   ///< a module failed, or the mission did
inline constexpr int kExitInvalid = 2;  ///< an invalid manifest or command line, or a goal refused at once
inline constexpr int kExitNoPath = 3;   ///< the planner found the goal cannot be reached; the vehicle landed

/// Something that acts on a run while it flies.
class RunExtension {
public:
  virtual ~RunExtension() = default;
  /// Every pass of the run's loop (about every 50 ms) once all modules have started.
  virtual void tick(LaunchRun& run) = 0;
  /// True to end the run (stopping its modules as Ctrl-C would, without failing it).
  virtual bool done() const { return false; }
  /// The run is about to stop its modules, which still run: the last moment to ask them for
  /// anything (call run.service() to wait for answers).
  virtual void ending(LaunchRun& /*run*/) {}
  /// After the modules stopped: the exit code the extension's verdict makes of `code`.
  virtual int finish(LaunchRun& run, int code) = 0;
};

class LaunchRun {
public:
  /// `dir`: the run's folder for logs and the summary.
  LaunchRun(const launch::Manifest& manifest, const LaunchOptions& options, std::filesystem::path dir, int domain);
  ~LaunchRun();

  /// Runs to the end; 0 when nothing failed and the mission (if any) succeeded, else 1.
  int execute(RunExtension* extension = nullptr);

  // What an extension may do and see.
  /// Pumps output, handles exits and pending restarts; false once the run must end.
  bool service(int timeout_ms);
  const launch::Manifest& manifest() const { return m_; }
  launch::Observer& observer() { return *observer_; }
  const launch::HostNetwork& network() const { return *net_; }
  const std::filesystem::path& logDir() const { return supervisor_.logDir(); }
  int domain() const { return domain_; }
  bool running(const std::string& module) const { return supervisor_.running(module); }
  std::optional<pid_t> pid(const std::string& module) const { return supervisor_.pid(module); }
  /// Sends `signal` to a module's process group; when `exit_expected` its exit does not fail
  /// the run (supervision still respawns it as the manifest says). False if it is not running.
  bool signalModule(const std::string& module, int signal, bool exit_expected);
  /// Stops a running module (SIGTERM, then SIGKILL after the grace period) and starts it again;
  /// starts it now if it is not running.
  void restartModule(const std::string& module);
  /// A line of the launcher's, on the console and in launch.log.
  void say(const std::string& line) { supervisor_.say(line); }
  /// report.html and its figures in the run's folder, from the run's recording.
  void writeReport();
  /// Why the run failed (a module, the recorder, a timeout); empty while nothing failed.
  const std::string& failure() const { return failure_; }
  /// A module marked `ends_run` whose exit ended the run (normally, or killed by a fault):
  /// which, when (steady wall time) and why. Nothing while the run goes on, or when it ended
  /// otherwise.
  struct EndedBy {
    std::string module;
    std::int64_t wall_ns = 0;
    std::string reason;
  };
  const std::optional<EndedBy>& endedBy() const { return ended_by_; }
  /// The mission summary, once the run ended (nothing without a mission).
  const std::optional<launch::MissionSummary>& summary() const { return summary_; }

  /// Set by the signal handler `quad launch` and `quad fault` install.
  static std::atomic<int> received_signal;

private:
  struct State {
    int restarts = 0;
    std::int64_t restart_at_ns = 0;  // 0: none pending
    bool started = false;
    bool exit_expected = false;      // a fault stops it: its exit is not a failure
    std::optional<int> last_status;
    std::set<std::string> beating;   // the modules whose heartbeat came since its start
  };

  void startModule(const launch::Module& mod);
  /// A module's heartbeat: a started module whose process it came from is running.
  void onHeartbeat(const launch::ModuleBeat& beat);
  /// Rewrites <run folder>/run.json from record_ (and the failure, if any).
  void saveRecord();
  /// The run ends before any module started (failure_ says why): records it, returns `code`.
  int endedBeforeStart(int code);
  void handleExit(const launch::Supervisor::Exit& e);
  std::string whoWrites(const std::string& topic) const;
  /// Says, for each module, the last line its log has about lockstep ("lockstep: ...").
  void reportStall();
  /// The known-map optimum from `world`'s start to its goal, with the run's planning module's
  /// parameters; nothing when the run has no planner or no path exists.
  std::optional<double> knownMapOptimum(const world::World& world);
  /// Publishes each vehicle's goal and follows its mission; kExitInvalid (failure_ says why)
  /// when a goal or a fleet's start is refused at once.
  int startMissions();
  /// The mission's summary once the modules stopped: the vehicle's, or the fleet's with each
  /// vehicle's.
  launch::MissionSummary missionSummary(double wall_s);
  /// What each process of the run cost, once they all stopped, and the launcher itself.
  std::vector<launch::ProcessCost> processCosts() const;
  void stopAll();
  bool waitForNeeds(const launch::Module& mod);
  /// Until every reader of the mission's goal discovered so far holds it (5 s at most).
  void waitForGoalDelivery();
  const launch::Module& module(const std::string& name) const;
  bool interrupted() const { return received_signal.load() != 0; }

  const launch::Manifest& m_;
  const LaunchOptions& options_;
  int domain_;
  launch::Supervisor supervisor_;
  std::filesystem::path state_dir_;  // ${run_state}
  std::unique_ptr<launch::HostNetwork> net_;
  std::unique_ptr<launch::Observer> observer_;
  std::map<std::string, std::string> env_;
  std::map<std::string, State> states_;
  std::vector<std::string> started_order_;
  std::optional<std::string> recorder_host_;  // the container hosting the run's recorder (composed), if one does
  bool failed_ = false;
  std::optional<EndedBy> ended_by_;  // set: a module that ends the run exited (normally, or by a fault)
  std::string failure_;
  std::int64_t start_ns_;
  std::optional<launch::MissionSummary> summary_;
  launch::RunRecord record_;
};

/// Loads and validates `options.manifest` with the options' overrides (world, mode, domain,
/// subnet); every problem goes to stderr as `file:key: value: reason`. Nothing when invalid.
std::optional<launch::Manifest> loadRunManifest(const LaunchOptions& options);

/// Runs a loaded manifest (in its own log folder unless `options.log_dir`); the exit code.
int runManifest(const launch::Manifest& manifest, const LaunchOptions& options, RunExtension* extension);

/// The planner's setup of a manifest: its planning module's config with the planner's keys
/// of its `set` (the node's own, such as state.source, do not shape a path). Nothing without a
/// planning module; throws common::ConfigError for a bad config or world.
std::optional<plan::PlanningSetup> manifestPlanningSetup(const launch::Manifest& manifest);

/// "demo-20261122-101500-4242": a run folder's name.
std::string runFolderName(const std::string& name);

}  // namespace quad::launch
