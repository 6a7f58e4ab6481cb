// SPDX-License-Identifier: BSD-3-Clause
// Launch manifests: what a valid one gives, and how each kind of mistake is refused.
#include "quad/launch/manifest.hpp"

#include <algorithm>
#include <gtest/gtest.h>

#include <fstream>

#include "quad/common/params.hpp"
#include "quad/common/payload_header.hpp"

namespace quad::launch {
namespace {

namespace fs = std::filesystem;

/// A scratch project: bringup/ for manifests, a build tree with fake module programs.
class ManifestTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    root_ = fs::temp_directory_path() / ("quad_manifest_test_" + std::to_string(::getpid()));
    fs::create_directories(root_ / "bringup");
    fs::create_directories(root_ / "configs/worlds");
    for (const char* m : {"plant", "mapping", "planning", "control"}) {
      const fs::path p = root_ / "build/modules" / m / "node" / (std::string("quad_") + m + "_node");
      fs::create_directories(p.parent_path());
      std::ofstream(p) << "#!/bin/sh\n";
    }
    fs::create_directories(root_ / "build/tools/container");
    std::ofstream(root_ / "build/tools/container/quad_container") << "#!/bin/sh\n";
    std::ofstream(root_ / "configs/plant.yaml") << "sim: {mode: realtime}\n";
    std::ofstream(root_ / "configs/worlds/w.yaml") << "bounds: {min: [0, 0, 0], max: [1, 1, 1]}\n";
    // A topic's owner, as its contract says: the function in its name (quad/sim/...: the plant).
    lookup_ = {{false, root_, root_ / "build"}, [](const std::string& t) -> std::optional<std::string> {
                 if (!t.starts_with("quad/") || t.find('/', 5) == std::string::npos) {
                   return std::nullopt;
                 }
                 const std::string function = t.substr(5, t.find('/', 5) - 5);
                 return function == "sim" ? "plant" : function;
               }};
  }
  void TearDown() override { fs::remove_all(root_); }

  Manifest parse(const std::string& yaml, ManifestOverrides overrides = {})
  {
    return parseManifest(yaml, root_ / "bringup/m.yaml", overrides, lookup_);
  }

  /// The problems a manifest is refused with.
  std::vector<std::string> problems(const std::string& yaml)
  {
    try {
      parse(yaml);
    } catch (const common::ConfigError& e) {
      return e.problems();
    }
    ADD_FAILURE() << "accepted:\n" << yaml;
    return {};
  }

  /// Whether one of `problems` holds `text`.
  static bool has(const std::vector<std::string>& problems, const std::string& text)
  {
    return std::any_of(problems.begin(), problems.end(), [&](const std::string& p) { return p.find(text) != std::string::npos; });
  }

  fs::path root_;
  ProgramLookup lookup_;
};

TEST_F(ManifestTest, AValidManifestResolvesProgramsPathsAndVariables)
{
  const Manifest m = parse(R"(
world: ../configs/worlds/w.yaml
hosts:
  a: {type: local}
  b: {type: netns}
modules:
  plant:
    host: b
    config: ../configs/plant.yaml
    set: {world: "${world}", sim.mode: "${mode}"}
    needs: [quad/control/actuators]
    respawn: 2
    ends_run: true
  control: {}
)");
  ASSERT_EQ(m.modules.size(), 2U);
  const Module& plant = m.modules[0];
  EXPECT_EQ(plant.kind, "plant");
  EXPECT_EQ(plant.host, "b");
  EXPECT_EQ(plant.program, root_ / "build/modules/plant/node/quad_plant_node");
  EXPECT_EQ(plant.config, root_ / "configs/plant.yaml");
  ASSERT_EQ(plant.sets.size(), 2U);
  EXPECT_EQ(plant.sets[0].second, (root_ / "configs/worlds/w.yaml").string());
  EXPECT_EQ(plant.sets[1].second, "lockstep");
  EXPECT_EQ(plant.respawn, 2);
  EXPECT_TRUE(plant.ends_run);
  EXPECT_EQ(m.modules[1].host, "a");  // the first host by default
  EXPECT_TRUE(m.usesNamespaces());
  EXPECT_EQ(m.discovery, Discovery::kMulticast);
}

TEST_F(ManifestTest, CommandLineOverridesWin)
{
  ManifestOverrides o;
  o.mode = "realtime";
  o.domain = 17;
  o.subnet = "10.99.1";
  const Manifest m = parse("domain: 3\nmodules: {control: {}}\n", o);
  EXPECT_EQ(m.mode, "realtime");
  EXPECT_EQ(*m.domain, 17);
  EXPECT_EQ(m.subnet, "10.99.1");
}

TEST_F(ManifestTest, AModulesParameterFromTheCommandLineReplacesTheManifestsOrIsAdded)
{
  ManifestOverrides o;
  o.sets = {parseModuleSet("control:follower.max_speed=7", "--set"), parseModuleSet("control:a.b=x=y", "--set"),
            parseModuleSet("plant:sim.seed=4", "--set")};
  o.layout = "composed";
  const Manifest m = parse(R"(
modules:
  control: {set: {follower.max_speed: 2.0, other: 1}}
  plant: {}
containers: {fast: [plant, control]}
)", o);
  const auto sets = [&](const std::string& name) {
    const Module* mod = const_cast<Manifest&>(m).findHostedModule(name);
    return mod ? mod->sets : std::vector<std::pair<std::string, std::string>>{};
  };
  // in the composed layout, the hosted modules' copies have them
  EXPECT_EQ(sets("control"), (std::vector<std::pair<std::string, std::string>>{
                                 {"follower.max_speed", "7"}, {"other", "1"}, {"a.b", "x=y"}}));
  EXPECT_EQ(sets("plant"), (std::vector<std::pair<std::string, std::string>>{{"sim.seed", "4"}}));

  ManifestOverrides unknown;
  unknown.sets = {parseModuleSet("planer:x=1", "--set")};
  try {
    parse("modules: {control: {}, plant: {}}\n", unknown);
    FAIL() << "accepted";
  } catch (const common::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1U);
    EXPECT_NE(e.problems()[0].find("--set planer:x: 1: no module 'planer' in the manifest (modules: control, plant)"),
              std::string::npos)
        << e.problems()[0];
  }
  for (const std::string bad : {"control", "control:x", ":x=1", "control:=1", "x=1"}) {
    EXPECT_THROW(parseModuleSet(bad, "--set"), common::ConfigError) << bad;
  }
}

TEST_F(ManifestTest, TheStateFlownOnIsTheEstimateUnlessTheManifestOrTheCommandLineSaysTruth)
{
  const std::string text = "modules:\n  control: {set: {state.source: \"${state}\"}}\n";
  const Manifest estimate = parse(text);
  EXPECT_EQ(estimate.state, "estimate");
  ASSERT_EQ(estimate.modules[0].sets.size(), 1U);
  EXPECT_EQ(estimate.modules[0].sets[0].second, "estimate");
  EXPECT_EQ(parse("state: truth\n" + text).modules[0].sets[0].second, "truth");
  ManifestOverrides o;
  o.state = "truth";
  EXPECT_EQ(parse("state: estimate\n" + text, o).state, "truth");
  const auto p = problems("state: guess\n" + text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":state: guess:"), std::string::npos) << p[0];
}

TEST_F(ManifestTest, AParticipantLeaseIsTakenInWholeSecondsAndABadOneNamed)
{
  EXPECT_EQ(parse("modules: {control: {}}\n").participant_lease_s, 0);  // the QoS profile's
  EXPECT_EQ(parse("discovery: {lease: 20}\nmodules: {control: {}}\n").participant_lease_s, 20);
  EXPECT_EQ(parse("discovery: {kind: server, lease: 30}\nmodules: {control: {}}\n").participant_lease_s, 30);
  for (const std::string lease : {"0.5", "2.5", "-3", "soon"}) {
    const auto p = problems("discovery: {lease: " + lease + "}\nmodules: {control: {}}\n");
    ASSERT_EQ(p.size(), 1U) << lease;
    EXPECT_NE(p[0].find("discovery.lease: " + lease), std::string::npos) << p[0];
  }
}

TEST_F(ManifestTest, UnknownKeyIsRefusedWithFileAndKey)
{
  const auto p = problems("modules:\n  control: {respawns: 2}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_EQ(p[0].rfind((root_ / "bringup/m.yaml").string() + ":modules.control.respawns: 2: unknown key", 0), 0U)
      << p[0];
}

TEST_F(ManifestTest, UnknownHostIsRefused)
{
  const auto p = problems("hosts: {a: {type: local}}\nmodules:\n  control: {host: b}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":modules.control.host: b: unknown host (hosts: a)"), std::string::npos) << p[0];
}

TEST_F(ManifestTest, ModuleNotFoundIsRefused)
{
  auto p = problems("modules:\n  autopilot: {}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":modules.autopilot.module: autopilot: module not found"), std::string::npos) << p[0];
  fs::remove(root_ / "build/modules/control/node/quad_control_node");
  p = problems("modules:\n  control: {}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find("module not built"), std::string::npos) << p[0];
}

TEST_F(ManifestTest, EveryProblemIsListedAtOnce)
{
  const auto p = problems(R"(
transport: carrier-pigeon
hosts: {a: {type: netns, address: 1.2.3.4}}
modules:
  control: {config: missing.yaml, needs: [not/a/topic], set: {x: "${nope}"}}
)");
  EXPECT_EQ(p.size(), 5U);
  for (const char* key : {":transport: carrier-pigeon", ":hosts.a.address: 1.2.3.4", ":modules.control.config: missing.yaml",
                          ":modules.control.needs[0]: not/a/topic", ":modules.control.set.x: ${nope}: unknown variable"}) {
    EXPECT_TRUE(std::any_of(p.begin(), p.end(), [&](const std::string& s) { return s.find(key) != std::string::npos; }))
        << key;
  }
}

TEST_F(ManifestTest, SecurityNamesAnInitialisedFolder)
{
  auto p = problems("security: ../keys\nmodules: {control: {}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":security: ../keys: no ca.pem in "), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("quad security init"), std::string::npos) << p[0];
  fs::create_directories(root_ / "keys");
  std::ofstream(root_ / "keys/ca.pem") << "certificate\n";
  std::ofstream(root_ / "keys/governance.p7s") << "signed\n";
  const Manifest m = parse("security: ../keys\nmodules: {control: {}}\n");
  EXPECT_EQ(m.security_dir.lexically_normal(), (root_ / "keys").lexically_normal());
}

TEST_F(ManifestTest, NetworkRestrictionsAndFirewallAreReadAndChecked)
{
  const Manifest m = parse(R"(
network: {interfaces: hosts, firewall: true}
hosts:
  a: {type: netns}
  b: {type: ssh, address: pilot@192.168.1.20}
  c: {type: local, interfaces: [192.168.1.10]}
modules: {control: {host: a}}
)");
  EXPECT_TRUE(m.restrict_interfaces);
  EXPECT_TRUE(m.firewall);
  EXPECT_EQ(m.host("c").interfaces, std::vector<std::string>{"192.168.1.10"});
  EXPECT_FALSE(parse("modules: {control: {}}\n").restrict_interfaces);

  const auto p = problems(R"(
network: {interfaces: some, firewall: yes}
hosts: {a: {type: local, interfaces: [eth0]}}
modules: {control: {}}
)");
  EXPECT_EQ(p.size(), 3U);
  for (const char* key : {":network.interfaces: some: expected one of: any, hosts", ":network.firewall: yes: expected bool",
                          ":hosts.a.interfaces[0]: eth0: not an IPv4 address"}) {
    EXPECT_TRUE(std::any_of(p.begin(), p.end(), [&](const std::string& s) { return s.find(key) != std::string::npos; }))
        << key;
  }
  // An ssh host known by name needs its addresses; a firewall needs a host to go on.
  auto q = problems("network: {interfaces: hosts}\nhosts: {b: {type: ssh, address: pilot@uav1}}\nmodules: {control: {host: b}}\n");
  ASSERT_EQ(q.size(), 1U);
  EXPECT_NE(q[0].find(":hosts.b.interfaces: hosts: network.interfaces: hosts needs this ssh host's IPv4 addresses"),
            std::string::npos)
      << q[0];
  q = problems("network: {firewall: true}\nmodules: {control: {}}\n");
  ASSERT_EQ(q.size(), 1U);
  EXPECT_NE(q[0].find(":network.firewall: true: no netns or ssh host to install it on"), std::string::npos) << q[0];
}

TEST_F(ManifestTest, TheGeofenceReachesThePlannerAndTheControllerOnly)
{
  const Manifest m = parse(R"(
geofence: {min: [-1, -2.5, 0], max: [20, 2.5, 6]}
modules:
  plant: {}
  planning: {}
  control: {set: {autostart: true}}
)");
  ASSERT_TRUE(m.geofence.has_value());
  EXPECT_EQ(m.geofence->min[1], -2.5);
  EXPECT_TRUE(m.modules[0].sets.empty());
  const std::vector<std::pair<std::string, std::string>> fence{{"geofence.min", "[-1, -2.5, 0]"},
                                                               {"geofence.max", "[20, 2.5, 6]"}};
  EXPECT_EQ(m.modules[1].sets, fence);
  ASSERT_EQ(m.modules[2].sets.size(), 3U);
  EXPECT_EQ(m.modules[2].sets[1], fence[0]);
  EXPECT_EQ(m.modules[2].sets[2], fence[1]);
}

TEST_F(ManifestTest, ABadGeofenceOrOneGivenToAModuleAloneIsRefused)
{
  auto p = problems("geofence: {min: [0, 0, 5], max: [1, 1, 1]}\nmodules: {control: {}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":geofence.min: [0, 0, 5]: not below geofence.max on the z axis"), std::string::npos) << p[0];
  p = problems("geofence: {min: [0, 0], max: [1, 1, 1]}\nmodules: {control: {}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":geofence.min: "), std::string::npos) << p[0];
  p = problems("modules: {planning: {set: {geofence.max: \"[1, 1, 1]\"}}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":modules.planning.set.geofence.max: [1, 1, 1]: give the run's keep-in volume as the manifest's "
                      "geofence"),
            std::string::npos)
      << p[0];
}

TEST_F(ManifestTest, AMissionNeedsAWorld)
{
  const auto p = problems("modules: {control: {}}\nmission: {tolerance: 0.5}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":mission: "), std::string::npos) << p[0];
}

TEST_F(ManifestTest, AMissionIsScoredOnFiftyStatesASecondUnlessItSaysOtherwise)
{
  const std::string head = "world: ../configs/worlds/w.yaml\nmodules: {control: {}}\n";
  EXPECT_DOUBLE_EQ(parse(head + "mission: {tolerance: 0.5}\n").mission.score_rate_hz, 50.0);
  EXPECT_DOUBLE_EQ(parse(head + "mission: {score_rate: 0}\n").mission.score_rate_hz, 0.0);  // every state
  const auto p = problems(head + "mission: {score_rate: -1}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find("mission.score_rate"), std::string::npos) << p[0];
}

/// A fleet manifest of two vehicles in the scratch world, with `extra` lines at the end.
std::string fleetManifest(const std::string& extra = "")
{
  return R"(
world: ../configs/worlds/w.yaml
hosts: {a: {type: local}, b: {type: netns}}
vehicles:
  - {id: 4, start: [0.2, 0.2, 0], goal: [0.8, 0.8, 0.5], hosts: {planning: b}}
  - {id: 7, start: [0.8, 0.2, 0]}
modules:
  mapping: {set: {checkpoint.file: "${run_state}/mapping.checkpoint"}}
  planning: {needs: [quad/mapping/update]}
  plant: {config: ../configs/plant.yaml, set: {world: "${world}"}, ends_run: true}
)" + extra;
}

TEST_F(ManifestTest, AFleetRunsEachModuleOncePerVehicleAndThePlantOnceForAll)
{
  const Manifest m = parse(fleetManifest());
  ASSERT_EQ(m.vehicles.size(), 2U);
  EXPECT_EQ(m.vehicleIds(), (std::vector<std::uint32_t>{4, 7}));
  EXPECT_EQ(m.vehicles[0].start, (std::array<double, 3>{0.2, 0.2, 0.0}));
  EXPECT_EQ(m.vehicles[0].goal, (std::array<double, 3>{0.8, 0.8, 0.5}));
  EXPECT_FALSE(m.vehicles[1].goal.has_value());  // the world's
  std::vector<std::string> names;
  for (const Module& mod : m.modules) {
    names.push_back(mod.name);
  }
  // Start order: each module's instances together, in the manifest's order.
  EXPECT_EQ(names, (std::vector<std::string>{"mapping.4", "mapping.7", "planning.4", "planning.7", "plant"}));
  const Module& mapping = m.modules[1];
  EXPECT_EQ(mapping.vehicle, 7U);
  ASSERT_EQ(mapping.sets.size(), 1U);
  EXPECT_EQ(mapping.sets[0].second, std::string(kRunStateVariable) + "/vehicle7/mapping.checkpoint");
  EXPECT_EQ(m.modules[2].host, "b");  // vehicle 4's planner, as its hosts say
  EXPECT_EQ(m.modules[3].host, "a");
  EXPECT_EQ(m.modules[2].needs, (std::vector<std::string>{"quad/mapping/update"}));
  const Module& plant = m.modules[4];
  EXPECT_FALSE(plant.vehicle.has_value());
  ASSERT_EQ(plant.sets.size(), 2U);
  EXPECT_EQ(plant.sets[1], (std::pair<std::string, std::string>{"fleet", std::string(kRunStateVariable) + "/" + kFleetFile}));
  EXPECT_EQ(fleetFileText(m.vehicles),
            "# Written by quad launch from the manifest's vehicles.\nvehicles:\n"
            "  - {id: 4, start: [0.2, 0.2, 0], goal: [0.8, 0.8, 0.5]}\n"
            "  - {id: 7, start: [0.8, 0.2, 0]}\n");
}

TEST_F(ManifestTest, AComposedFleetHasEachVehiclesContainerAndOnePlant)
{
  // Vehicle 4's planner runs on host b in fleetManifest(): not with its mapper.
  std::string text = fleetManifest("containers: {slow: [mapping, planning]}\nlayout: composed\n");
  text.replace(text.find(", hosts: {planning: b}"), std::string(", hosts: {planning: b}").size(), "");
  const Manifest m = parse(text);
  std::vector<std::string> names;
  for (const Module& mod : m.modules) {
    names.push_back(mod.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"slow.4", "slow.7", "plant"}));
  const Module& seven = m.modules[1];
  EXPECT_EQ(seven.kind, kContainerKind);
  EXPECT_EQ(seven.vehicle, 7U);  // its process's QUAD_VEHICLE_ID
  ASSERT_EQ(seven.hosted.size(), 2U);
  EXPECT_EQ(seven.hosted[0].name, "mapping.7");
  EXPECT_EQ(seven.hosted[1].name, "planning.7");
  EXPECT_EQ(seven.hosted[0].sets[0].second, std::string(kRunStateVariable) + "/vehicle7/mapping.checkpoint");
  EXPECT_TRUE(seven.needs.empty());  // the map update is its own mapper's
  EXPECT_FALSE(m.modules[2].vehicle.has_value());
  EXPECT_EQ(m.processOf("planning.4"), &m.modules[0]);
  ASSERT_EQ(m.containers.size(), 2U);
  EXPECT_EQ(m.containers[1].modules, (std::vector<std::string>{"mapping.7", "planning.7"}));

  // The plant serves every vehicle; a vehicle's modules must share its host.
  EXPECT_TRUE(has(problems(fleetManifest("containers: {fast: [planning, plant]}\nlayout: composed\n")),
                  "containers.fast[1]: plant: 'plant' serves every vehicle of the fleet"));
  const auto apart = problems(fleetManifest("containers: {slow: [mapping, planning]}\nlayout: composed\n"));
  EXPECT_TRUE(has(apart, "containers.slow.4: "));
  EXPECT_TRUE(has(apart, "planning.4 runs on b and mapping.4 on a: a container's modules share one host"));
  EXPECT_TRUE(has(problems(fleetManifest("containers: {planning: [mapping]}\n")),
                  "containers.planning: planning: already a module's name"));
}

TEST_F(ManifestTest, OneVehicleOfAFleetIsFlownAloneOnRequest)
{
  ManifestOverrides o;
  o.vehicle = 7;
  const Manifest m = parse(fleetManifest(), o);
  ASSERT_EQ(m.vehicles.size(), 1U);
  EXPECT_EQ(m.vehicleIds(), std::vector<std::uint32_t>{7});
  std::vector<std::string> names;
  for (const Module& mod : m.modules) {
    names.push_back(mod.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"mapping.7", "planning.7", "plant"}));
  EXPECT_EQ(fleetFileText(m.vehicles),
            "# Written by quad launch from the manifest's vehicles.\nvehicles:\n  - {id: 7, start: [0.8, 0.2, 0]}\n");
  o.vehicle = 5;
  try {
    parse(fleetManifest(), o);
    ADD_FAILURE() << "a vehicle the fleet does not have";
  } catch (const common::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1U);
    EXPECT_NE(e.problems()[0].find(":vehicles: "), std::string::npos) << e.problems()[0];
    EXPECT_NE(e.problems()[0].find("no vehicle 5 (--vehicle): its ids are 4, 7"), std::string::npos) << e.problems()[0];
  }
  try {
    parse("modules: {control: {}}\n", o);
    ADD_FAILURE() << "--vehicle of a manifest of one vehicle";
  } catch (const common::ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1U);
    EXPECT_NE(e.problems()[0].find("this one lists none"), std::string::npos) << e.problems()[0];
  }
}

TEST_F(ManifestTest, AManifestWithoutVehiclesFliesVehicleZero)
{
  const Manifest m = parse("modules: {control: {}}\n");
  EXPECT_TRUE(m.vehicles.empty());
  EXPECT_EQ(m.vehicleIds(), (std::vector<std::uint32_t>{0}));
  EXPECT_FALSE(m.modules[0].vehicle.has_value());
}

TEST_F(ManifestTest, FleetMistakesAreRefusedNamingTheVehicleAndKey)
{
  auto p = problems(fleetManifest("  control: {}\n").replace(fleetManifest().find("id: 7"), 5, "id: 4"));
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles[1].id: 4: already the id of vehicles[0]"), std::string::npos) << p[0];
  std::string text = fleetManifest();
  text.replace(text.find("start: [0.8, 0.2, 0]"), 20, "start: [0.8, 0.2]");
  p = problems(text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles[1].start: "), std::string::npos) << p[0];
  text = fleetManifest();
  text.replace(text.find("planning: b"), 11, "planning: c");
  p = problems(text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles[0].hosts.planning: c: unknown host"), std::string::npos) << p[0];
  text = fleetManifest();
  text.replace(text.find("planning: b"), 11, "control: b");
  p = problems(text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles[0].hosts.control: b: no module 'control' in modules"), std::string::npos) << p[0];
  text = fleetManifest();
  text.replace(text.find("  plant:"), std::string::npos, "");
  p = problems(text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles: "), std::string::npos) << p[0];
  EXPECT_NE(p[0].find("one plant module; the manifest has 0"), std::string::npos) << p[0];
  text = fleetManifest();
  text.replace(text.find("set: {world:"), 12, "set: {fleet: f.yaml, world:");
  p = problems(text);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":modules.plant.set.fleet: f.yaml: the launcher writes"), std::string::npos) << p[0];
  p = problems("world: ../configs/worlds/w.yaml\nvehicles: []\nmodules: {plant: {}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles: "), std::string::npos) << p[0];
  std::string crowd = "world: ../configs/worlds/w.yaml\nvehicles:\n";
  for (int id = 1; id <= common::kMaxFleetVehicles + 1; ++id) {
    crowd += "  - {id: " + std::to_string(id) + ", start: [0, 0, 0]}\n";
  }
  p = problems(crowd + "modules: {plant: {}}\n");
  ASSERT_EQ(p.size(), 1U);
  EXPECT_NE(p[0].find(":vehicles: 65 vehicles: at most 64 fly in one domain"), std::string::npos) << p[0];
}

TEST_F(ManifestTest, TheShippedManifestsAreValid)
{
  ProgramLookup shipped{{false, QUAD_SOURCE_DIR, QUAD_BUILD_DIR}, {}};
  for (const char* name : {"demo.yaml", "fast.yaml", "fleet.yaml", "three_hosts.yaml"}) {
    EXPECT_NO_THROW(loadManifest(fs::path(QUAD_SOURCE_DIR) / "bringup" / name, {}, shipped)) << name;
  }
}

/// The demo's shape: modules in start order, two containers.
constexpr const char* kComposable = R"(
world: ../configs/worlds/w.yaml
hosts: {a: {type: local}, b: {type: netns}}
modules:
  mapping: {set: {world: "${world}"}}
  planning: {needs: [quad/mapping/update]}
  control: {needs: [quad/planning/path], respawn: 1}
  plant:
    config: ../configs/plant.yaml
    set: {sim.mode: "${mode}"}
    needs: [quad/control/actuators, quad/mapping/update]
    ends_run: true
containers:
  slow: [mapping, planning]
  fast: [plant, control]
)";

TEST_F(ManifestTest, TheDistributedLayoutRunsAProcessPerModuleAndKeepsTheContainersForTheOther)
{
  const Manifest m = parse(kComposable);
  EXPECT_EQ(m.layout, "distributed");
  ASSERT_EQ(m.modules.size(), 4U);
  ASSERT_EQ(m.containers.size(), 2U);
  EXPECT_EQ(m.containers[1].name, "fast");
  EXPECT_EQ(m.containers[1].modules, (std::vector<std::string>{"plant", "control"}));
  EXPECT_TRUE(m.modules[0].hosted.empty());
}

TEST_F(ManifestTest, TheComposedLayoutRunsEachContainerAsOneProcessInItsFirstModulesPlace)
{
  ManifestOverrides o;
  o.layout = "composed";
  const Manifest m = parse(kComposable, o);
  EXPECT_EQ(m.layout, "composed");
  ASSERT_EQ(m.modules.size(), 2U);
  const Module& slow = m.modules[0];
  const Module& fast = m.modules[1];
  EXPECT_EQ(slow.name, "slow");
  EXPECT_EQ(slow.kind, kContainerKind);
  EXPECT_EQ(slow.program, root_ / "build/tools/container/quad_container");
  const std::string program = (root_ / "build/tools/container/quad_container").string();
  EXPECT_EQ(processCommand(slow, "/state"),
            (std::vector<std::string>{program, "--module", "mapping", "--set",
                                      "world=" + (root_ / "configs/worlds/w.yaml").string(), "--module", "planning"}));
  EXPECT_TRUE(slow.needs.empty());  // the map update is its own mapper's
  EXPECT_FALSE(slow.ends_run);
  // In start order (control before the plant), each with its config and sets.
  ASSERT_EQ(fast.hosted.size(), 2U);
  EXPECT_EQ(fast.hosted[0].name, "control");
  EXPECT_EQ(fast.hosted[1].kind, "plant");
  EXPECT_EQ(processCommand(fast, "/state"),
            (std::vector<std::string>{program, "--module", "control", "--module", "plant", "--config",
                                      (root_ / "configs/plant.yaml").string(), "--set", "sim.mode=lockstep"}));
  // What others write, once each; not the actuators its own controller writes.
  EXPECT_EQ(fast.needs, (std::vector<std::string>{"quad/planning/path", "quad/mapping/update"}));
  EXPECT_TRUE(fast.ends_run);
  EXPECT_EQ(fast.respawn, 1);
  EXPECT_TRUE(fast.config.empty());
  EXPECT_TRUE(fast.sets.empty());
  // The modules themselves, as the manifest gives them, for what reads their settings.
  std::vector<std::string> hosted;
  for (const Module* mod : m.hostedModules()) {
    hosted.push_back(mod->name);
  }
  EXPECT_EQ(hosted, (std::vector<std::string>{"mapping", "planning", "control", "plant"}));
  EXPECT_EQ(fast.hosted[1].config, root_ / "configs/plant.yaml");
  EXPECT_EQ(m.findModule("plant"), nullptr);
  EXPECT_EQ(m.processOf("plant"), &fast);
  EXPECT_EQ(m.processOf("slow"), nullptr);  // a process, not a module
  // A hosted module changed (a fault scenario's sets) is started so.
  Manifest changed = m;
  changed.findHostedModule("control")->sets.emplace_back("follower.max_speed", "3");
  EXPECT_EQ(processCommand(changed.modules[1], "/state")[3], "--set");
  EXPECT_EQ(processCommand(changed.modules[1], "/state")[4], "follower.max_speed=3");
  // The manifest still says which layout could run it the other way.
  EXPECT_EQ(parse("layout: composed\n" + std::string(kComposable)).modules.size(), 2U);
}

TEST_F(ManifestTest, ContainerMistakesAreRefusedNamingTheContainerAndModule)
{
  const std::string modules = "hosts: {a: {type: local}, b: {type: netns}}\n"
                              "modules: {plant: {}, control: {host: b}, mapping: {}}\n";
  auto p = problems(modules + "containers: {fast: [plant, nothing]}\n");
  EXPECT_TRUE(has(p, "containers.fast[1]: nothing: no module 'nothing' in modules")) << p.front();
  p = problems(modules + "containers: {fast: [plant], other: [plant]}\n");
  EXPECT_TRUE(has(p, "containers.other[0]: plant: 'plant' is already in container fast")) << p.front();
  p = problems(modules + "containers: {plant: [control]}\n");
  EXPECT_TRUE(has(p, "containers.plant: plant: already a module's name")) << p.front();
  p = problems(modules + "layout: composed\n");
  EXPECT_TRUE(has(p, "layout: composed: the composed layout hosts the modules of 'containers', and there are none"))
      << p.front();
  p = problems(modules + "layout: composed\ncontainers: {fast: [plant, control]}\n");
  EXPECT_TRUE(has(p, "containers.fast: ") && has(p, "control runs on b and plant on a: a container's modules share one host"))
      << p.front();
  fs::create_directories(root_ / "sec");
  std::ofstream(root_ / "sec/ca.pem") << "";
  std::ofstream(root_ / "sec/governance.p7s") << "";
  // With DDS Security a container is one participant with one identity, made for it.
  const std::string secured = "security: ../sec\nlayout: composed\nmodules: {plant: {}, mapping: {}}\n"
                              "containers: {all: [mapping, plant]}\n";
  p = problems(secured);
  // Named as its participant is: its modules in start order, not the container's list.
  EXPECT_TRUE(has(p, "containers.all: ") && has(p, "no plant+mapping.pem in ") &&
              has(p, ": a container has one identity; make it with quad security init ") &&
              has(p, " --container plant,mapping"))
      << (p.empty() ? "" : p.front());
  std::ofstream(root_ / "sec/plant+mapping.pem") << "";
  EXPECT_NO_THROW(parse(secured));
  p = problems(modules + "layout: apart\ncontainers: {fast: [plant]}\n");
  EXPECT_TRUE(has(p, "layout: apart: expected one of: composed, distributed")) << p.front();
}

}  // namespace
}  // namespace quad::launch
