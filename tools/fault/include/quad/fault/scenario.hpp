// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A fault-injection scenario (tests/scenarios/*.yaml): the manifest to launch, a timeline of
/// faults in sim time, what the stack must do after each, and how the run must end. No DDS:
/// `quad fault` applies it; docs/fault-injection.md describes the format.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quad/common/geofence.hpp"
#include "quad/wire/datagram_faults.hpp"
#include "quad/launch/link_faults.hpp"
#include "quad/launch/manifest.hpp"
#include "quad/plant/faults.hpp"

namespace quad::fault {

/// What a step does to the running stack.
struct Action {
  enum class Kind {
    kKill,     ///< SIGKILL to a module's process group
    kPause,    ///< SIGSTOP
    kResume,   ///< SIGCONT
    kRestart,  ///< stop (SIGTERM, then SIGKILL) and start again
    kPlant,    ///< a plant fault, applied by the plant node (quad/system/fault)
    kPublish,  ///< samples published on a topic (bad inputs)
    kDds,      ///< datagram faults in a module's DDS fault layer (quad/system/fault)
    kLink,     ///< a fault on a network-namespace host's link (iptables, ip link)
    kMark,     ///< nothing: the step marks the time its expectations count from (the fault is
               ///< the scenario's set-up, `set:`, such as a small battery)
    kOperatorLink,  ///< the operator's station (the launcher) stops its heartbeat: the link is lost
  };
  Kind kind = Kind::kKill;
  std::string module;              ///< process actions
  plant::Fault plant;              ///< kPlant (its id is the step's number)
  std::string topic;               ///< kPublish
  std::string values;              ///< kPublish: the sample's fields in YAML, as `quad topic pub` takes them
  /// kPublish: list fields repeated to these lengths, past their IDL bounds if so (the
  /// sample is then encoded as given: an oversized sequence).
  std::map<std::string, std::size_t> lengths;
  int count = 1;                   ///< kPublish: how many samples
  double rate_hz = 10.0;           ///< kPublish: at this rate
  /// kDds: the faults on what `module` receives, ids `kDatagramIdBase * step + 1..5`.
  std::vector<wire::DatagramFault> datagrams;
  launch::LinkFault link;            ///< kLink
  std::string note;                  ///< kMark: what the scenario's set-up does, in words
  /// kDds, kLink, kOperatorLink: cleared (healed) this long after; absent: when the run ends.
  std::optional<double> duration_s;

  /// A fault that lasts until it is cleared, and whose clearing the report shows.
  bool lasts() const { return kind == Kind::kDds || kind == Kind::kLink || kind == Kind::kOperatorLink; }

  /// "kill planning", "plant: fault 3 motor: rotor 2 at 0.5 efficiency", ...
  std::string describe() const;
};

/// Datagram fault ids are `kDatagramIdBase * step + k`: apart from step numbers, which
/// name the fault tool's own events and plant faults.
inline constexpr std::uint32_t kDatagramIdBase = 1000;
inline constexpr std::size_t kMaxSteps = 999;

/// What must follow a step, and how soon.
struct Expectation {
  enum class Kind {
    kMode,      ///< the controller reports `mode` within `within_s` of sim time
    kNoticed,   ///< the launcher's readers see `module` lose liveliness within `within_s` wall seconds
    kBack,      ///< `module` runs again (a heartbeat from a new process) within `within_s` wall seconds
    kRejected,  ///< `module`'s count of rejected inputs (its heartbeat's errors) grows within `within_s` wall seconds
    /// the vehicle's altitude stays within `metres` below its altitude at the fault for
    /// `within_s` of sim time
    kAltitudeLost,
    kRunEnded,  ///< the launcher ends the run because `module` (ends_run) is gone, within `within_s` wall seconds
    /// the estimator's count of refused samples of the sensor `module` names (position, baro,
    /// mag: its gate's outliers, quad/estimation/state) grows within `within_s` of sim time
    kOutliers,
  };
  /// Where a kMode bound is measured from.
  enum class Since {
    kFault,     ///< the moment the step's fault took effect
    kLastPath,  ///< the stamp of the last path a controller would fly (PLAN_OK, finite waypoints):
                ///< a reaction to the path going stale, its timeout included in `within_s`
  };
  Kind kind = Kind::kMode;
  std::string mode;    ///< kMode: a ControlMode name without its prefix ("HOVER")
  std::string module;  ///< kNoticed, kBack, kRejected, kRunEnded: a module; kOutliers: a sensor
  double within_s = 1.0;
  Since since = Since::kFault;
  double metres = 0.0;  ///< kAltitudeLost: the most altitude the vehicle may lose

  bool simTime() const { return kind == Kind::kMode || kind == Kind::kAltitudeLost || kind == Kind::kOutliers; }
  /// "mode HOVER", "noticed planning", "altitude lost", ...
  std::string describe() const;
};

struct Step {
  double at_s = 0.0;  ///< sim time it is due
  Action action;
  std::vector<Expectation> expect;
};

/// How the run must end.
struct Outcome {
  enum class Mission { kSuccess, kFailure, kCrashed, kAny };  ///< kCrashed: a failure that ended crashed
  Mission mission = Mission::kSuccess;
  int max_collisions = 0;
  bool finite_actuators = true;   ///< no actuator command with a non-finite rotor speed
  bool zero_loss = true;          ///< the recording lost nothing on reliable topics
  /// A fleet's run: how each vehicle named here must end its own mission (`mission` above is
  /// the whole fleet's).
  std::map<std::uint32_t, Mission> vehicles;
};

struct Scenario {
  std::filesystem::path file;
  std::string name;
  std::string description;
  std::filesystem::path manifest;             ///< absolute
  std::optional<std::filesystem::path> world; ///< absolute; replaces the manifest's
  std::optional<std::string> mode;            ///< "realtime" | "lockstep"; replaces the manifest's
  std::optional<std::string> state;           ///< "estimate" | "truth"; replaces the manifest's
  std::optional<common::Geofence> geofence;   ///< the keep-in volume; replaces the manifest's
  std::optional<double> end_s;                ///< sim time to end the run at (before the mission ends)
  /// A fleet's run: the vehicle whose controller, paths, state and estimate the expectations
  /// watch, and the one plant faults act on; unset: the manifest's first (or only) vehicle.
  std::optional<std::uint32_t> vehicle;
  /// Per module, parameters it gets over the manifest's (`--set key=value`): the weather,
  /// a vehicle's fault-prone settings.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> sets;
  std::vector<Step> steps;                    ///< in time order
  Outcome outcome;
};

/// What a scenario can name, checked against the manifest and the IDL by the caller.
struct ScenarioLookup {
  std::vector<std::string> modes;  ///< ControlMode names ("HOVER", ...)
  /// Why `values` (YAML) cannot be published on `topic`; empty when it can.
  std::function<std::string(const std::string& topic, const std::string& values)> check_sample;
};

/// Every problem as `file:key: value: reason` in a common::ConfigError.
Scenario parseScenario(std::string_view yaml_text, const std::filesystem::path& file, const ScenarioLookup& lookup);
Scenario loadScenario(const std::filesystem::path& file, const ScenarioLookup& lookup);

/// Problems of a scenario against the manifest it launches (modules or hosts it names that
/// the manifest lacks; a plant fault without a plant; a link fault on a host that is not a
/// network namespace), as `file:key: value: reason`. `hosts`: each host, and whether it is
/// a network namespace.
std::vector<std::string> checkAgainstModules(const Scenario& scenario, const std::vector<std::string>& modules,
                                             const std::vector<std::string>& kinds,
                                             const std::map<std::string, bool>& hosts = {});

/// Problems of a scenario's vehicles (`vehicle`, `outcome.vehicles`) against the manifest's
/// (`vehicle_ids`; `fleet`: the manifest lists vehicles), as `file:key: value: reason`.
std::vector<std::string> checkAgainstVehicles(const Scenario& scenario, const std::vector<std::uint32_t>& vehicle_ids,
                                              bool fleet);

/// Problems of a scenario against the manifest's containers in the composed layout: a step
/// that kills, pauses, resumes, restarts or breaks the datagrams of a module that shares its
/// process with others (it would break them all).
std::vector<std::string> checkAgainstContainers(const Scenario& scenario, const launch::Manifest& manifest);

}  // namespace quad::fault
