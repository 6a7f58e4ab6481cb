// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Launch manifests (bringup/*.yaml): which module runs on which host, with which config,
/// on which DDS domain and discovery, gated on which topics, restarted how. Read and
/// validated whole before anything starts; every problem is `file:key: value: reason`.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quad/common/geofence.hpp"
#include "quad/common/layout.hpp"

namespace quad::launch {

enum class HostKind { kLocal, kNetns, kSsh };
/// "local", "netns", "ssh": a host's `type` in a manifest.
std::string_view toString(HostKind kind);
enum class Discovery { kMulticast, kInitialPeers, kServer };

struct Host {
  std::string name;
  HostKind kind = HostKind::kLocal;
  std::string address;  ///< ssh: user@host or host; netns: assigned at launch (empty here)
  int ssh_port = 22;
  std::string root;     ///< ssh: the project's checkout on that machine; empty = same as here
  std::vector<std::string> ssh_options;  ///< ssh: more ssh arguments (-i KEY, -o ...)
  /// This host's IPv4 addresses DDS may use with `network.interfaces: hosts`; empty: the
  /// address the run reaches it at.
  std::vector<std::string> interfaces;
};

struct Module {
  std::string name;
  std::string kind;                          ///< the quad module it runs ("plant", ...); "" for a program
  std::string host;                          ///< a key of Manifest::hosts
  std::filesystem::path program;             ///< absolute, resolved
  std::vector<std::string> args;             ///< after --config/--set, variables expanded
  std::filesystem::path config;              ///< absolute; empty = the module's defaults
  std::vector<std::pair<std::string, std::string>> sets;  ///< --set KEY=VALUE, expanded
  std::map<std::string, std::string> environment;
  std::vector<std::string> needs;            ///< topics with a live writer before it starts
  double ready_timeout_s = 20.0;
  int respawn = 0;                           ///< restarts allowed after a failure
  double backoff_s = 1.0;                    ///< first restart delay, doubled each time
  bool ends_run = false;                     ///< its normal exit ends the run
  /// In a fleet manifest: the vehicle this instance of the module serves (its
  /// QUAD_VEHICLE_ID); nothing for a module that serves the whole run (the plant).
  std::optional<std::uint32_t> vehicle;
  /// A container of the composed layout (kind kContainerKind): the modules it hosts, as the
  /// manifest gives them, in start order; empty for a process of one module.
  std::vector<Module> hosted;
};

/// The kind of a Module that hosts several (`containers:` in the composed layout).
inline constexpr const char* kContainerKind = "container";

/// `containers:` one process hosting several modules in the composed layout.
struct ContainerSpec {
  std::string name;                  ///< its process's name in the run, as a module's
  std::vector<std::string> modules;  ///< the manifest names of the modules it hosts
};

/// One vehicle of a fleet manifest (`vehicles:`), as the plant's fleet file has it.
struct FleetMember {
  std::uint32_t id = 0;                       ///< its modules' QUAD_VEHICLE_ID, its samples' Header.vehicle_id
  std::array<double, 3> start{};              ///< [m] where it stands when the run begins
  std::optional<std::array<double, 3>> goal;  ///< [m] its mission's goal; unset: the world's
  std::filesystem::path vehicle;              ///< its vehicle file (absolute); the mission's when not given
};

struct Mission {
  bool enabled = false;
  double tolerance_m = 0.4;   ///< goal reached within this distance
  bool land = true;           ///< land once the goal is reached
  double timeout_s = 180.0;   ///< sim seconds before the mission counts as failed
  std::filesystem::path vehicle;  ///< its radius turns centre distances into clearances
  double score_rate_hz = 50.0;    ///< true and estimated states scored per second of sim time; 0: every one
};

struct Manifest {
  std::filesystem::path file;
  std::string name;
  std::optional<int> domain;        ///< unset: QUAD_DOMAIN_ID or 0
  std::string transport = "udp";    ///< QUAD_TRANSPORT of every process
  Discovery discovery = Discovery::kMulticast;
  std::string discovery_host;       ///< the server's host (kServer)
  int discovery_port = 11811;
  /// How long the run's participants keep one they do not hear from [s]; 0: the QoS profile's
  /// (2 s). A machine too loaded to announce every participant within it (a large lockstep
  /// fleet on few cores) needs a longer one (docs/fleet.md).
  int participant_lease_s = 0;
  std::string subnet = "10.77.0";   ///< netns hosts: <subnet>.1 the bridge, .2... the hosts
  std::filesystem::path world;      ///< ${world}; empty when the manifest names none
  std::string mode = "lockstep";    ///< ${mode}: lockstep | realtime
  /// ${state}: what the stack flies on, estimate | truth (the modules' state.source)
  std::string state = "estimate";
  std::uint64_t seed = 1;           ///< ${seed}: for the modules' random draws (the plant's sim.seed)
  double grace_s = 5.0;             ///< SIGTERM to SIGKILL
  /// DDS Security for every process of the run (QUAD_SECURITY_DIR): the folder of
  /// `quad security init`; empty: off.
  std::filesystem::path security_dir;
  /// `network.interfaces: hosts`: every process's DDS only on its host's addresses
  /// (QUAD_INTERFACES), not on every interface it has.
  bool restrict_interfaces = false;
  /// `network.firewall`: on each netns and ssh host, firewall rules admit the domain's DDS
  /// ports only from the manifest's hosts (firewall.hpp).
  bool firewall = false;
  std::map<std::string, std::string> environment;
  std::vector<Host> hosts;          ///< in the order written
  /// A fleet manifest's vehicles; empty for one vehicle (the world's start and goal). Each
  /// module but the plant then runs once per vehicle (Module::vehicle), named
  /// fleetInstanceName(module, id), and the plant simulates them all (kFleetFile).
  std::vector<FleetMember> vehicles;
  std::vector<Module> modules;      ///< start order (a fleet's: each module's instances together)
  /// `layout`: "distributed", every module a process of its own (the default), or "composed",
  /// each of the `containers` one process on its modules' one host (`modules` then holds it
  /// in the place of its first module).
  std::string layout = "distributed";
  /// In a fleet, each container of the manifest once per vehicle, of its instances
  /// (fleetInstanceName of the container and of each module); the plant is in none.
  std::vector<ContainerSpec> containers;
  Mission mission;
  /// `geofence: {min: [x, y, z], max: [x, y, z]}`: the keep-in volume [m], handed to every
  /// planning and control module as its geofence.min and geofence.max (common::geofenceSets).
  std::optional<common::Geofence> geofence;

  const Host& host(const std::string& host_name) const;
  /// The module of that name; nullptr when there is none (the launcher's own processes).
  /// In the composed layout, a container is one and the modules it hosts are not.
  const Module* findModule(const std::string& module_name) const;
  /// Every module the run hosts, alone or in a container, in start order.
  std::vector<const Module*> hostedModules() const;
  /// The module of that name, alone or in a container; nullptr when there is none. Changes to
  /// a hosted one (its sets) reach its container's command line (processCommand).
  Module* findHostedModule(const std::string& module_name);
  /// The process that runs the module of that name: itself, or its container; nullptr when
  /// there is none.
  const Module* processOf(const std::string& module_name) const;
  bool usesNamespaces() const;
  /// The ids of the vehicles the run flies: the fleet's, or {0} for one vehicle.
  std::vector<std::uint32_t> vehicleIds() const;
};

/// "planning.2": the instance of a module that serves one vehicle of a fleet.
std::string fleetInstanceName(const std::string& module_name, std::uint32_t vehicle_id);
/// The fleet file the launcher writes for the plant in the run's state folder, from the
/// manifest's vehicles (the plant's `fleet` key names it).
inline constexpr const char* kFleetFile = "fleet.yaml";
/// "vehicle2": one vehicle's folder in a fleet's run: within the run's state folder, its
/// modules' ${run_state} (two vehicles' mappers do not share a checkpoint); within the run's
/// folder, its report.
std::string vehicleFolder(std::uint32_t vehicle_id);
/// The fleet file's text: the vehicles with their ids, starts, goals and vehicle files.
std::string fleetFileText(const std::vector<FleetMember>& vehicles);

/// What the command line changes in a manifest before it is checked.
/// `${run_state}`: left as it is in a module's `set`, `args` and `environment` values, for the
/// run to fill with its state folder (<run folder>/state, absolute: emptied when the run
/// starts, kept across the modules' restarts within it).
inline constexpr const char* kRunStateVariable = "${run_state}";

/// `text` with every ${run_state} replaced by `state_dir`: a module's command line and
/// environment for its run (the launcher), or for a replay of it (quad replay --compare).
std::string withRunState(std::string text, const std::filesystem::path& state_dir);

/// The command line `mod`'s process starts with, ${run_state} replaced by `state_dir`: its
/// program, --config, --set KEY=VALUE and args; a container's, quad_container with each
/// hosted module's --module KIND, --config and --set, as the hosted modules are now.
std::vector<std::string> processCommand(const Module& mod, const std::filesystem::path& state_dir);

/// `--set MODULE:KEY=VALUE`: one parameter of one module of the manifest, given on the
/// command line (quad launch, a campaign's sweep); it replaces the manifest's `set` of that
/// key, or adds one. In a fleet it reaches every vehicle's instance of the module.
struct ModuleSet {
  std::string module;
  std::string key;
  std::string value;
};

/// "control:follower.max_speed=7" read as a ModuleSet; throws common::ConfigError naming
/// `origin` (the option or file key it came from) and the text when it is not one.
ModuleSet parseModuleSet(const std::string& text, const std::string& origin);

struct ManifestOverrides {
  std::optional<std::filesystem::path> world;
  std::optional<std::string> mode;
  std::optional<std::string> state;
  std::optional<std::uint64_t> seed;
  std::optional<int> domain;
  std::optional<std::string> subnet;
  std::optional<common::Geofence> geofence;
  /// A fleet manifest: keep this vehicle of its list alone (`quad launch --vehicle`).
  std::optional<std::uint32_t> vehicle;
  std::optional<std::string> layout;  ///< `quad launch --layout`
  std::vector<ModuleSet> sets;        ///< `quad launch --set`, applied in order
};

/// What a manifest is checked against: where modules' programs are (common::programPath of
/// the layout: the build tree or an installed prefix), `${root}` (the layout's data folder)
/// and which topic names exist.
struct ProgramLookup {
  common::Layout layout;
  /// The module that writes a topic ("plant", "every module"), nothing for no such topic:
  /// `needs` are checked with it, and a container does not wait for what its own modules
  /// write. Unset: any name, owners unknown.
  std::function<std::optional<std::string>(const std::string&)> topic_owner;
};

/// The manifest `name_or_path` names: an existing file as it is; a bare name ("demo") the
/// layout's bringup/<name>.yaml when that exists; else as given (reading it then fails,
/// naming it).
std::filesystem::path findManifest(const std::string& name_or_path, const common::Layout& layout);

/// Reads and validates a manifest. Relative paths are relative to the manifest's folder;
/// `${world}`, `${mode}`, `${state}`, `${seed}` and `${root}` are expanded in module args, sets and environment;
/// `${run_state}` is left for the run (kRunStateVariable).
/// Throws common::ConfigError listing every problem.
Manifest loadManifest(const std::filesystem::path& file, const ManifestOverrides& overrides,
                      const ProgramLookup& lookup);

/// Same, from text; `origin` names it in messages and its folder anchors relative paths.
Manifest parseManifest(const std::string& text, const std::filesystem::path& origin,
                       const ManifestOverrides& overrides, const ProgramLookup& lookup);

}  // namespace quad::launch
