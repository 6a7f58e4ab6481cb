// SPDX-License-Identifier: BSD-3-Clause
// The plant node as a process: real time, lockstep determinism, faults, bad configuration, a
// fleet of vehicles.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_lines.hpp"
#include "module_wait.hpp"
#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

/// A file of this test's, in its folder.
std::filesystem::path testFile(const std::string& name)
{
  const auto dir = std::filesystem::temp_directory_path() / "quad_plant_node_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

/// Writes a plant config next to the shipped ones (so its relative paths resolve) and
/// returns its path.
std::string config(const std::string& name, const std::string& body)
{
  const auto path = testFile(name);
  std::ofstream(path) << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\n"
                      << "world: " << QUAD_CONFIG_DIR << "/worlds/demo.yaml\n"
                      << body;
  return path.string();
}

// x500: sqrt(m g / (4 k_f)) = sqrt(2 * 9.81 / (4 * 8.54858e-6))
const std::string kHover = "757.5";

/// The plant's SIM_EVENT_RUN_ENDED event as `quad topic echo --json` printed it (its stamp is
/// the final sim time, its p_W the final position, at full precision); null when none came.
nlohmann::json runEnded(ChildProcess& events)
{
  events.waitForOutput("SIM_EVENT_RUN_ENDED", 10s);
  for (const auto& e : quad::test::jsonLines(events.output())) {
    if (e["kind"] == "SIM_EVENT_RUN_ENDED") {
      return e;
    }
  }
  return nullptr;
}

TEST(PlantNode, RealTimeRunPublishesStateAndStopsAtItsDuration)
{
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, env(140));
  ChildProcess plant({QUAD_PLANT_NODE, "--config", config("realtime.yaml", "sim: {duration: 3.0}\n")}, env(140));
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/state", "-n", "3", "--timeout", "10"}, env(140));
  EXPECT_EQ(echo.wait(15s), 0) << echo.output();
  EXPECT_NE(echo.output().find("landed: true"), std::string::npos) << echo.output();
  EXPECT_EQ(plant.wait(15s), 0) << plant.output();
  // The run ends at its duration of sim time, and says so on its events topic
  const nlohmann::json ended = runEnded(events);
  ASSERT_FALSE(ended.is_null()) << events.output();
  EXPECT_EQ(ended["header"]["stamp_ns"], 3'000'000'000LL) << ended;
}

/// The run's end (SIM_EVENT_RUN_ENDED) of a lockstep run of 4 s. Such a run lasts well under a
/// second of wall time, so the events reader is matched before the run starts: the plant waits
/// for the controller's first command, and the controller starts once the reader is seen.
nlohmann::json lockstepRun(int domain)
{
  ChildProcess plant({QUAD_PLANT_NODE, "--config",
                      config("lockstep.yaml", "sim: {mode: lockstep, duration: 4.0, seed: 5}\n")},
                     env(domain));
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, env(domain));
  EXPECT_TRUE(quad::test::waitForReader(domain, "quad/sim/events", 15s));
  ChildProcess controller({QUAD_ALTITUDE_CONTROLLER, kHover, "2.0"}, env(domain));
  EXPECT_EQ(plant.wait(60s), 0) << plant.output();
  return runEnded(events);
}

TEST(PlantNode, TwoLockstepRunsWithOneSeedAreBitIdentical)
{
  // GIVEN a controller whose commands depend on the state they answer
  // WHEN two lockstep runs of 4 s fly it (their wall-clock timing differs)
  const nlohmann::json a = lockstepRun(141);
  const nlohmann::json b = lockstepRun(142);
  // THEN they end at the same sim time at the same position, to the last bit, and the
  // vehicle did climb
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  EXPECT_EQ(a["header"]["stamp_ns"], 4'000'000'000LL) << a;
  EXPECT_EQ(a["header"]["stamp_ns"], b["header"]["stamp_ns"]);
  EXPECT_EQ(a["p_W"].dump(17), b["p_W"].dump(17));
  EXPECT_GT(a["p_W"]["z"].get<double>(), 1.0) << a;
}

TEST(PlantNode, FaultCommandIsAcknowledgedOnTheEventsTopic)
{
  ChildProcess plant({QUAD_PLANT_NODE, "--config", config("faults.yaml", "sim: {duration: 20.0}\n")}, env(143));
  ASSERT_TRUE(quad::test::waitForRunningModule(143, "plant", 20s)) << plant.output();
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "-n", "3", "--timeout", "15"}, env(143));
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/fault",
                    "{fault_id: 9, module_name: plant, kind: FAULT_MOTOR_FAILURE, index: 1, magnitude: 0.5}"},
                   env(143));
  ASSERT_EQ(pub.wait(15s), 0) << pub.output();
  ChildProcess bad({QUAD_TOOL, "topic", "pub", "quad/system/fault",
                    "{fault_id: 10, module_name: plant, kind: FAULT_DATAGRAM_LOSS, magnitude: 0.5}"},
                   env(143));
  ASSERT_EQ(bad.wait(15s), 0) << bad.output();
  EXPECT_EQ(events.wait(20s), 0) << events.output();
  EXPECT_NE(events.output().find("kind: SIM_EVENT_FAULT_APPLIED"), std::string::npos) << events.output();
  EXPECT_NE(events.output().find("detail: fault 9 motor: rotor 1 at 0.5 efficiency"), std::string::npos)
      << events.output();
  EXPECT_NE(events.output().find("kind: SIM_EVENT_FAULT_REJECTED"), std::string::npos) << events.output();
}

TEST(PlantNode, BadWorldIsRefusedNamingFileKeyAndValue)
{
  const auto dir = std::filesystem::temp_directory_path() / "quad_plant_node_test";
  std::filesystem::create_directories(dir);
  const auto world = dir / "bad_world.yaml";
  std::ofstream(world) << "bounds: {min: [0, 0, 0], max: [10, 10, 10]}\nstart: [1, 1, 0]\ngoal: [9, 9, 2]\n"
                          "obstacles:\n  - {type: sphere, center: [5, 5, 5], radius: .nan}\n";
  const auto path = dir / "bad.yaml";
  std::ofstream(path) << "world: " << world.string() << "\n";
  ChildProcess plant({QUAD_PLANT_NODE, "--config", path.string()}, env(144));
  EXPECT_EQ(plant.wait(10s), 1) << plant.output();
  EXPECT_NE(plant.output().find(world.string() + ":obstacles[0].radius: .nan: not a finite number"),
            std::string::npos)
      << plant.output();
}

/// A fleet file beside the test's configs.
std::string fleetFile(const std::string& name, const std::string& body)
{
  const auto path = testFile(name);
  std::ofstream(path) << body;
  return path.string();
}

TEST(PlantNode, AFleetFliesInOneWorldEachVehicleUnderItsIdAndTwoThatMeetCollide)
{
  // GIVEN two vehicles of one fleet, the second 1.2 m above the first, which stands on the
  // ground: without commands it falls onto it (their 0.35 m spheres meet after 0.5 m)
  const std::string fleet =
      fleetFile("fleet.yaml", "vehicles:\n  - {id: 1, start: [0, 0, 0]}\n  - {id: 2, start: [0, 0, 1.2]}\n");
  auto eventsOf = [](const char* vehicle) {
    return std::make_unique<ChildProcess>(
        std::vector<std::string>{QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json", "--vehicle", vehicle},
        env(70));
  };
  const std::map<int, std::unique_ptr<ChildProcess>> events = [&] {
    std::map<int, std::unique_ptr<ChildProcess>> m;
    m[1] = eventsOf("1");
    m[2] = eventsOf("2");
    return m;
  }();
  // WHEN one plant simulates the fleet for 3 s of sim time
  ChildProcess plant({QUAD_PLANT_NODE, "--config", config("fleet_plant.yaml", "fleet: " + fleet + "\nsim: {duration: 3.0}\n")},
                     env(70));
  ChildProcess state2(
      {QUAD_TOOL, "topic", "echo", "quad/sim/state", "--vehicle", "2", "-n", "1", "--json", "--timeout", "10"}, env(70));
  // THEN each vehicle's samples come under its own id, from where it is: the second's
  // state, read alone, is the second's
  EXPECT_EQ(state2.wait(15s), 0) << state2.output();
  const auto states = quad::test::jsonLines(state2.output());
  ASSERT_EQ(states.size(), 1U) << state2.output();
  EXPECT_EQ(states[0]["header"]["vehicle_id"], 2) << states[0];
  EXPECT_GT(states[0]["p_W"]["z"].get<double>(), 0.0) << states[0];
  EXPECT_EQ(plant.wait(20s), 0) << plant.output();
  // AND each vehicle's events, read alone, are its own, numbered 1, 2, 3, ... on their own:
  // it collided once, both at the same time, and its run ended with that one collision
  std::map<int, std::int64_t> collided;
  for (const auto& [vehicle, echo] : events) {
    echo->waitForOutput("SIM_EVENT_RUN_ENDED", 20s);
    const auto lines = quad::test::jsonLines(echo->output());
    std::vector<std::int64_t> collisions;
    std::optional<nlohmann::json> ended;
    for (std::size_t k = 0; k < lines.size(); ++k) {
      const auto& e = lines[k];
      EXPECT_EQ(e["header"]["vehicle_id"], vehicle) << e;
      EXPECT_EQ(e["header"]["seq"], k + 1) << echo->output();
      if (e["kind"] == "SIM_EVENT_COLLISION") {
        collisions.push_back(e["header"]["stamp_ns"].get<std::int64_t>());
      } else if (e["kind"] == "SIM_EVENT_RUN_ENDED") {
        ended = e;
      }
    }
    ASSERT_EQ(collisions.size(), 1U) << echo->output();
    collided[vehicle] = collisions[0];
    ASSERT_TRUE(ended.has_value()) << echo->output();
    EXPECT_EQ((*ended)["subject_id"], 1) << *ended;
    EXPECT_EQ((*ended)["header"]["stamp_ns"], 3'000'000'000LL) << *ended;
  }
  EXPECT_EQ(collided[1], collided[2]);
  // 0.5 m of free fall: about 0.32 s
  EXPECT_NEAR(static_cast<double>(collided[1]) * 1e-9, 0.32, 0.03);
}

/// Each vehicle's SIM_EVENT_RUN_ENDED of a 4 s lockstep run of a fleet of two, each flown by
/// a controller of its own to its own altitude (vehicle 1 to 2 m, vehicle 2 to 3 m).
std::map<int, nlohmann::json> fleetLockstepRun(int domain)
{
  const std::string fleet =
      fleetFile("lockstep_fleet.yaml", "vehicles:\n  - {id: 1, start: [0, 0, 0]}\n  - {id: 2, start: [3, 0, 0]}\n");
  ChildProcess plant({QUAD_PLANT_NODE, "--config",
                      config("fleet_lockstep.yaml", "fleet: " + fleet + "\nsim: {mode: lockstep, duration: 4.0, seed: 5}\n")},
                     env(domain));
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, env(domain));
  EXPECT_TRUE(quad::test::waitForReader(domain, "quad/sim/events", 15s));
  auto as = [&](int vehicle) {
    auto e = env(domain);
    e["QUAD_VEHICLE_ID"] = std::to_string(vehicle);
    return e;
  };
  ChildProcess first({QUAD_ALTITUDE_CONTROLLER, kHover, "2.0"}, as(1));
  ChildProcess second({QUAD_ALTITUDE_CONTROLLER, kHover, "3.0"}, as(2));
  EXPECT_EQ(plant.wait(60s), 0) << plant.output();
  std::map<int, nlohmann::json> ended;
  for (int i = 0; i < 100 && ended.size() < 2; ++i) {
    events.waitForOutput("SIM_EVENT_RUN_ENDED", 1s);
    for (const auto& e : quad::test::jsonLines(events.output())) {
      if (e["kind"] == "SIM_EVENT_RUN_ENDED") {
        ended[e["header"]["vehicle_id"].get<int>()] = e;
      }
    }
  }
  return ended;
}

TEST(PlantNode, InLockstepEveryVehicleOfAFleetFliesOnItsOwnCommandsAndTwoRunsAreBitIdentical)
{
  // GIVEN two vehicles, each answered by a controller of its own (a command depends on the
  // state it answers), WHEN two lockstep runs fly them (their wall-clock timing differs)
  const auto a = fleetLockstepRun(74);
  const auto b = fleetLockstepRun(75);
  // THEN each vehicle climbed to its own altitude, and both runs end with every vehicle at
  // the same place, to the last bit: each round waited for every vehicle's command
  ASSERT_EQ(a.size(), 2U);
  ASSERT_EQ(b.size(), 2U);
  EXPECT_GT(a.at(1)["p_W"]["z"].get<double>(), 1.0) << a.at(1);
  EXPECT_GT(a.at(2)["p_W"]["z"].get<double>(), a.at(1)["p_W"]["z"].get<double>() + 0.5) << a.at(2);
  for (const int vehicle : {1, 2}) {
    EXPECT_EQ(a.at(vehicle)["header"]["stamp_ns"], 4'000'000'000LL) << a.at(vehicle);
    EXPECT_EQ(a.at(vehicle)["p_W"].dump(17), b.at(vehicle)["p_W"].dump(17)) << vehicle;
  }
}

/// The newest sim time on quad/sim/clock for `vehicle`, as a waiting plant resends it.
std::optional<std::int64_t> clockOf(int domain, const char* vehicle)
{
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "--vehicle", vehicle, "-n", "1", "--json",
                     "--timeout", "10"},
                    env(domain));
  if (echo.wait(15s) != 0) {
    return std::nullopt;
  }
  const auto samples = quad::test::jsonLines(echo.output());
  return samples.empty() ? std::nullopt : std::optional<std::int64_t>(samples.back()["sim_ns"].get<std::int64_t>());
}

TEST(PlantNode, InLockstepAFleetsClockWaitsForEachParticipantOfEveryVehicle)
{
  // GIVEN a fleet of two in lockstep, waiting for a participant "probe" and no command
  const std::string fleet =
      fleetFile("probe_fleet.yaml", "vehicles:\n  - {id: 1, start: [0, 0, 0]}\n  - {id: 2, start: [3, 0, 0]}\n");
  ChildProcess plant(
      {QUAD_PLANT_NODE, "--config",
       config("probe_plant.yaml", "fleet: " + fleet +
                                      "\nsim: {mode: lockstep}\nlockstep: {participants: probe, wait_for_command: false}\n")},
      env(76));
  auto report = [](const char* vehicle, const char* done_ns) {
    ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/sim/lockstep",
                      std::string("{participant: probe, done_ns: ") + done_ns + "}", "--vehicle", vehicle},
                     env(76));
    return pub.wait(20s);
  };
  // WHEN vehicle 1's probe is done up to 1 s
  ASSERT_EQ(report("1", "1000000000"), 0);
  // THEN the clock still waits at 0 for vehicle 2's probe
  EXPECT_EQ(clockOf(76, "1"), 0);
  // WHEN vehicle 2's probe is done up to 0.5 s
  ASSERT_EQ(report("2", "500000000"), 0);
  // THEN the clock runs to the round that ends past 0.5 s (4 ms rounds) and waits there, the
  // same for both vehicles
  std::optional<std::int64_t> now;
  for (int i = 0; i < 20 && now != 504'000'000; ++i) {
    now = clockOf(76, "2");
  }
  EXPECT_EQ(now, 504'000'000);
  EXPECT_EQ(clockOf(76, "1"), 504'000'000);
  plant.signal(SIGTERM);
  EXPECT_EQ(plant.wait(10s), 0) << plant.output();
}

TEST(PlantNode, AWaitingLockstepRoundSendsItsInputsAgainLessAndLessOften)
{
  // GIVEN a lockstep plant waiting for a participant that never reports
  const int domain = 201;
  ChildProcess plant({QUAD_PLANT_NODE, "--config",
                      config("silent_plant.yaml",
                             "sim: {mode: lockstep}\nlockstep: {participants: silent, wait_for_command: false}\n")},
                     env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "plant", 20s)) << plant.output();
  // past the first round (where the start-up's resends stay at every 20 ms)
  ChildProcess report({QUAD_TOOL, "topic", "pub", "quad/sim/lockstep", "{participant: silent, done_ns: 100000000}"},
                      env(domain));
  ASSERT_EQ(report.wait(20s), 0) << report.output();
  // WHEN its state is watched for 4 s of the wait
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/state", "-n", "100000", "--json", "--timeout", "4"},
                    env(domain));
  echo.wait(15s);
  // THEN the state came again (a lost sample is made good), each time the same round's, but
  // not every 20 ms (200 times): the interval doubles up to 0.64 s
  const auto states = quad::test::jsonLines(echo.output());
  EXPECT_GE(states.size(), 3U) << echo.output();
  EXPECT_LE(states.size(), 20U);
  for (const auto& s : states) {
    EXPECT_EQ(s["header"]["stamp_ns"], states.front()["header"]["stamp_ns"]) << s;
    EXPECT_GT(s["header"]["stamp_ns"].get<std::int64_t>(), 0) << s;
  }
  plant.signal(SIGTERM);
  EXPECT_EQ(plant.wait(10s), 0) << plant.output();
}

TEST(PlantNode, AFleetWhoseVehiclesStartInContactOrShareAnIdIsRefusedNamingTheFileAndThem)
{
  struct Case {
    const char* file;
    const char* vehicles;
    std::string says;  // after the fleet file's path
  };
  const Case cases[] = {
      {"touching.yaml", "  - {id: 4, start: [0, 0, 0]}\n  - {id: 7, start: [0.5, 0, 0]}\n",
       ": vehicles 4 and 7 start 0.500 m apart, in contact"},
      {"repeated.yaml", "  - {id: 4, start: [0, 0, 0]}\n  - {id: 4, start: [5, 0, 0]}\n",
       ":vehicles[1].id: 4: already the id of vehicles[0]"},
  };
  for (const Case& c : cases) {
    const std::string fleet = fleetFile(c.file, std::string("vehicles:\n") + c.vehicles);
    ChildProcess plant({QUAD_PLANT_NODE, "--config", config(std::string("plant_") + c.file, "fleet: " + fleet + "\n")},
                       env(71));
    EXPECT_EQ(plant.wait(10s), 1) << plant.output();
    EXPECT_NE(plant.output().find(fleet + c.says), std::string::npos) << plant.output();
  }
}

}  // namespace
