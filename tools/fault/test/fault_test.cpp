// SPDX-License-Identifier: BSD-3-Clause
// Fault scenarios: what a scenario file may say and the errors for what it may not, and the
// judge of a timeline: reaction times measured from when each fault took effect.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>

#include "quad/fault/judge.hpp"
#include "quad/fault/scenario.hpp"
#include "quad/common/params.hpp"
#include "scratch.hpp"

namespace quad::fault {
namespace {

namespace fs = std::filesystem;

ScenarioLookup lookup()
{
  ScenarioLookup l;
  l.modes = {"DISARMED", "IDLE", "TAKEOFF", "MISSION", "HOVER", "LAND", "FAILSAFE_LAND"};
  l.check_sample = [](const std::string& topic, const std::string& values) -> std::string {
    if (topic != "quad/sim/state") {
      return "no topic " + topic;
    }
    return values.find("nonsense") == std::string::npos ? "" : "no field nonsense in VehicleState";
  };
  return l;
}

/// A scenario file next to an empty manifest file, parsed.
class ScenarioFiles : public ::testing::Test {
protected:
  void SetUp() override
  {
    dir_ = test::scratchDir("fault_scenario");
    std::ofstream(dir_ / "manifest.yaml") << "name: x\n";
  }
  Scenario parse(const std::string& text) { return parseScenario(text, dir_ / "s.yaml", lookup()); }
  /// Every problem parsing `text` reports.
  std::vector<std::string> problems(const std::string& text)
  {
    try {
      parse(text);
    } catch (const common::ConfigError& e) {
      return e.problems();
    }
    return {};
  }
  static bool mentions(const std::vector<std::string>& problems, const std::string& what)
  {
    for (const auto& p : problems) {
      if (p.find(what) != std::string::npos) {
        return true;
      }
    }
    return false;
  }
  fs::path dir_;
};

TEST_F(ScenarioFiles, EveryFaultKindAndExpectationIsRead)
{
  const Scenario s = parse(R"(
name: all
manifest: manifest.yaml
mode: realtime
set: {plant: {wind.steady: "[0, 5, 0]", wind.turbulence_w20: 7.7}}
steps:
  - at: 5
    kill: planning
    expect: [{noticed: planning, within: 0.6}, {mode: HOVER, within: 1.5}, {back: planning, within: 4},
             {mode: HOVER, within: 1.1, since: last_path}]
  - {at: 6, pause: mapping}
  - {at: 7, resume: mapping}
  - {at: 8, restart: control, expect: [{altitude_lost: 0.5, within: 3}, {run_ended: plant, within: 0.5}]}
  - at: 9
    plant: {kind: motor, rotor: 2, efficiency: 0.5, duration: 3}
  - at: 10
    publish: {topic: quad/sim/state, values: {p_W: {x: .nan}}, count: 5, rate: 50}
    expect: [{rejected: control, within: 1}]
  - {at: 11, plant: {kind: cell_loss, cells: 2}}
  - {at: 12, mark: "a small battery", expect: [{mode: LAND, within: 30}]}
  - {at: 13, operator_link: {lost: true, duration: 6}}
  - at: 14
    plant: {kind: sensor_offset, sensor: position, offset: [0, 3, 0], duration: 0.5}
    expect: [{outliers: position, within: 0.3}]
outcome: {mission: failure, collisions: 2, finite_actuators: false, recording_loss: any}
)");
  EXPECT_EQ(s.name, "all");
  ASSERT_EQ(s.sets.count("plant"), 1U);
  EXPECT_EQ(s.sets.at("plant"), (std::vector<std::pair<std::string, std::string>>{
                                    {"wind.steady", "[0, 5, 0]"}, {"wind.turbulence_w20", "7.7"}}));
  EXPECT_EQ(s.mode, "realtime");
  ASSERT_EQ(s.steps.size(), 10U);
  ASSERT_EQ(s.steps[9].expect.size(), 1U);
  EXPECT_EQ(s.steps[9].expect[0].kind, Expectation::Kind::kOutliers);
  EXPECT_EQ(s.steps[9].expect[0].describe(), "outliers position");
  EXPECT_TRUE(s.steps[9].expect[0].simTime());
  EXPECT_EQ(s.steps[8].action.describe(), "operator link lost for 6 s");
  EXPECT_TRUE(s.steps[8].action.lasts());
  EXPECT_EQ(s.steps[0].action.describe(), "kill planning");
  ASSERT_EQ(s.steps[0].expect.size(), 4U);
  EXPECT_EQ(s.steps[0].expect[1].describe(), "mode HOVER");
  EXPECT_EQ(s.steps[0].expect[1].since, Expectation::Since::kFault);
  EXPECT_EQ(s.steps[0].expect[3].describe(), "mode HOVER after the last path");
  EXPECT_EQ(s.steps[0].expect[3].since, Expectation::Since::kLastPath);
  EXPECT_TRUE(s.steps[0].expect[1].simTime());
  EXPECT_FALSE(s.steps[0].expect[0].simTime());
  EXPECT_EQ(s.steps[1].action.kind, Action::Kind::kPause);
  EXPECT_EQ(s.steps[3].action.kind, Action::Kind::kRestart);
  ASSERT_EQ(s.steps[3].expect.size(), 2U);
  EXPECT_EQ(s.steps[3].expect[1].describe(), "run_ended plant");
  EXPECT_FALSE(s.steps[3].expect[1].simTime());
  EXPECT_EQ(s.steps[3].expect[0].kind, Expectation::Kind::kAltitudeLost);
  EXPECT_DOUBLE_EQ(s.steps[3].expect[0].metres, 0.5);
  EXPECT_DOUBLE_EQ(s.steps[3].expect[0].within_s, 3.0);
  EXPECT_TRUE(s.steps[3].expect[0].simTime());
  EXPECT_EQ(s.steps[4].action.kind, Action::Kind::kPlant);
  EXPECT_EQ(s.steps[4].action.plant.rotor, 2);
  EXPECT_EQ(s.steps[4].action.plant.id, 5U);  // the step's number
  EXPECT_EQ(s.steps[5].action.count, 5);
  EXPECT_DOUBLE_EQ(s.steps[5].action.rate_hz, 50.0);
  EXPECT_EQ(s.steps[6].action.describe(), "plant fault 7 cell_loss: 2 battery cells failed short");
  EXPECT_EQ(s.steps[7].action.kind, Action::Kind::kMark);
  EXPECT_EQ(s.steps[7].action.describe(), "mark: a small battery");
  ASSERT_EQ(s.steps[7].expect.size(), 1U);
  EXPECT_EQ(s.outcome.mission, Outcome::Mission::kFailure);
  EXPECT_EQ(s.outcome.max_collisions, 2);
  EXPECT_FALSE(s.outcome.finite_actuators);
  EXPECT_FALSE(s.outcome.zero_loss);
  EXPECT_EQ(s.manifest, dir_ / "manifest.yaml");
}

TEST_F(ScenarioFiles, MistakesAreNamedByKeyAndValue)
{
  const auto p = problems(R"(
manifest: nowhere.yaml
mode: sideways
set: {plant: [1, 2]}
steps:
  - {at: 5, kill: planning, pause: mapping}
  - {at: 4, explode: planning}
  - {at: 6, kill: planning, expect: [{mode: HOVERING, within: 1}]}
  - {at: 7, plant: {kind: motor, rotor: 7, efficiency: 0.5}}
  - {at: 8, publish: {topic: quad/sim/state, values: {nonsense: 1}}}
  - {at: -1, restart: control, expect: [{noticed: control}]}
  - {at: 9, kill: planning, expect: [{noticed: planning, within: 1, since: last_path}, {mode: HOVER, within: 1, since: noon}]}
  - {at: 10, kill: control, expect: [{altitude_lost: -1, within: 2}, {altitude_lost: 0.5}, {altitude_lost: 0.5, within: 1, since: last_path}]}
  - {at: 11, mark: [a, list]}
  - {at: 12, operator_link: {lost: false, for: 3}}
  - {at: 13, mark: "x", expect: [{outliers: imu, within: 1}]}
outcome: {mission: maybe, colisions: 1}
)");
  EXPECT_TRUE(mentions(p, "s.yaml:manifest: nowhere.yaml: no such file")) << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "mode: sideways: expected realtime or lockstep"));
  EXPECT_TRUE(mentions(p, "set.plant: [1, 2]: expected a map"));
  EXPECT_TRUE(mentions(p, "one fault per step, found kill, pause"));
  EXPECT_TRUE(mentions(p, "steps[1].explode: planning: unknown fault"));
  EXPECT_TRUE(mentions(p, "steps[2].expect[0].mode: HOVERING: not a controller mode"));
  EXPECT_TRUE(mentions(p, "steps[3].plant.rotor: 7"));
  EXPECT_TRUE(mentions(p, "steps[4].publish.values: {nonsense: 1}: no field nonsense in VehicleState"));
  EXPECT_TRUE(mentions(p, "steps[5].at: -1"));
  EXPECT_TRUE(mentions(p, "steps[5].expect[0].within"));
  EXPECT_TRUE(mentions(p, "steps[6].expect[0].since: last_path: only a mode expectation"));
  EXPECT_TRUE(mentions(p, "steps[6].expect[1].since: noon: expected fault or last_path"));
  EXPECT_TRUE(mentions(p, "steps[7].expect[0].altitude_lost: -1"));
  EXPECT_TRUE(mentions(p, "steps[7].expect[1].within"));
  EXPECT_TRUE(mentions(p, "steps[7].expect[2].since: last_path: only a mode expectation"));
  EXPECT_TRUE(mentions(p, "steps[8].mark: [a, list]: expected what the scenario's set-up does"));
  EXPECT_TRUE(mentions(p, "steps[9].operator_link.lost: false: expected true"));
  EXPECT_TRUE(mentions(p, "steps[9].operator_link.for: 3: unknown key"));
  EXPECT_TRUE(mentions(p, "steps[10].expect[0].outliers: imu: not a sensor the estimator gates (position, baro, mag)"));
  EXPECT_TRUE(mentions(p, "outcome.mission: maybe: expected success, failure, crashed or any"));
  EXPECT_TRUE(mentions(p, "outcome.colisions: 1: unknown key"));
}

TEST_F(ScenarioFiles, StepsOutOfOrderAndAnEndBeforeTheLastStepAreRefused)
{
  const auto p = problems(R"(
manifest: manifest.yaml
end_at: 6
steps:
  - {at: 8, kill: planning}
  - {at: 7, restart: planning}
outcome: {mission: success}
)");
  EXPECT_TRUE(mentions(p, "steps[1].at: 7: steps must be in time order")) << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "end_at: 6: earlier than the last step"));
  EXPECT_TRUE(mentions(p, "outcome.mission: success: a run ended by end_at has no mission outcome"));
}

TEST_F(ScenarioFiles, DatagramFaultsAreReadWithIdsApartFromStepNumbers)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
steps:
  - {at: 1, kill: mapping}
  - at: 2
    dds: {module: control, from: planning, loss: 0.2, delay: 0.02, corrupt: 0.01, seed: 9, duration: 60}
  - {at: 3, dds: {module: planning, duplicate: 0.5}}
)");
  ASSERT_EQ(s.steps.size(), 3U);
  const Action& a = s.steps[1].action;
  EXPECT_EQ(a.kind, Action::Kind::kDds);
  EXPECT_EQ(a.module, "control");
  ASSERT_EQ(a.datagrams.size(), 3U);
  EXPECT_EQ(a.datagrams[0].id, 2001U);
  EXPECT_EQ(a.datagrams[0].kind, wire::DatagramFaultKind::kLoss);
  EXPECT_EQ(a.datagrams[1].id, 2002U);
  EXPECT_DOUBLE_EQ(a.datagrams[1].magnitude, 0.02);
  EXPECT_EQ(a.datagrams[2].id, 2005U);
  for (const auto& d : a.datagrams) {
    EXPECT_EQ(d.from, "planning");
    EXPECT_EQ(d.seed, 9U);
  }
  EXPECT_EQ(a.duration_s, 60.0);
  EXPECT_EQ(a.describe(), "dds control <- planning: loss 0.2, delay 0.02 s, corrupt 0.01 (seed 9) for 60 s");
  const Action& b = s.steps[2].action;
  EXPECT_EQ(b.describe(), "dds planning <- every sender: duplicate 0.5 (seed 1)");
  EXPECT_FALSE(b.duration_s);
}

TEST_F(ScenarioFiles, BadDatagramFaultsAreNamedByKeyAndValue)
{
  const auto p = problems(R"(
manifest: manifest.yaml
steps:
  - {at: 1, dds: {module: control, loss: 1.5}}
  - {at: 2, dds: {module: control, delay: 12}}
  - {at: 3, dds: {module: control, jitter: 0.1, loss: 0.1}}
  - {at: 4, dds: {module: control, from: planning}}
  - {at: 5, dds: {loss: 0.1}}
)");
  EXPECT_TRUE(mentions(p, "steps[0].dds.loss: 1.5: loss 1.5: expected a probability in [0, 1]"))
      << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "steps[1].dds.delay: 12: delay 12: expected seconds in [0, 10]"));
  EXPECT_TRUE(mentions(p, "steps[2].dds.jitter"));
  EXPECT_TRUE(mentions(p, "steps[3].dds: "));
  EXPECT_TRUE(mentions(p, "no datagram fault: expected at least one of loss, delay, duplicate, reorder, corrupt"));
  EXPECT_TRUE(mentions(p, "steps[4].dds.module"));
}

TEST_F(ScenarioFiles, LinkFaultsAreReadAndCheckedAgainstTheManifestsHosts)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
steps:
  - {at: 1, link: {host: flight, loss: 0.2, duration: 10}}
  - {at: 2, link: {host: flight, partition: brain, duration: 3}}
  - {at: 3, link: {host: sim, down: true, duration: 1}}
)");
  ASSERT_EQ(s.steps.size(), 3U);
  EXPECT_EQ(s.steps[0].action.kind, Action::Kind::kLink);
  EXPECT_TRUE(s.steps[0].action.lasts());
  EXPECT_EQ(s.steps[0].action.describe(), "link loss 0.2 on flight's link for 10 s");
  EXPECT_EQ(s.steps[1].action.describe(), "link partition flight | brain for 3 s");
  EXPECT_EQ(s.steps[2].action.link.kind, launch::LinkFault::Kind::kDown);
  const std::map<std::string, bool> hosts = {{"sim", true}, {"brain", true}, {"flight", true}, {"local", false}};
  EXPECT_TRUE(checkAgainstModules(s, {"plant"}, {"plant"}, hosts).empty());
  const auto p = checkAgainstModules(s, {"plant"}, {"plant"}, {{"local", false}, {"flight", true}});
  EXPECT_TRUE(mentions(p, "steps[1].link.partition: brain: not a host of manifest.yaml")) << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "steps[2].link.host: sim: not a network-namespace host of manifest.yaml (flight)"));
  const auto q = checkAgainstModules(s, {"plant"}, {"plant"}, {{"local", false}});
  EXPECT_TRUE(mentions(q, "(it has none: link faults need hosts of type netns)")) << ::testing::PrintToString(q);

  const auto bad = problems(R"(
manifest: manifest.yaml
steps:
  - {at: 1, link: {host: flight, loss: 0}}
  - {at: 2, link: {host: flight, loss: 0.1, down: true}}
  - {at: 3, link: {host: flight, partition: flight}}
  - {at: 4, link: {host: flight, down: false}}
  - {at: 5, link: {host: flight}}
)");
  EXPECT_TRUE(mentions(bad, "steps[0].link.loss: 0: expected a probability in (0, 1]")) << ::testing::PrintToString(bad);
  EXPECT_TRUE(mentions(bad, "steps[1].link: "));
  EXPECT_TRUE(mentions(bad, "one link fault per step"));
  EXPECT_TRUE(mentions(bad, "steps[2].link.partition: flight: a host cannot be cut off from itself"));
  EXPECT_TRUE(mentions(bad, "steps[3].link.down: false: expected true"));
  EXPECT_TRUE(mentions(bad, "no link fault"));
}

TEST_F(ScenarioFiles, ModulesAreCheckedAgainstTheManifest)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
set: {sim: {wind.steady: "[1, 0, 0]"}}
steps:
  - {at: 1, kill: planner, expect: [{back: planner, within: 2}]}
  - {at: 2, plant: {kind: wind_gust, wind: [3, 0, 0], duration: 1}}
  - {at: 3, mark: "the set-up's fault"}
)");
  const auto p = checkAgainstModules(s, {"mapping", "planning"}, {"mapping", "planning"});
  EXPECT_FALSE(mentions(p, "steps[2]")) << "a mark names no module";
  EXPECT_TRUE(mentions(p, "set.sim: sim: not a module of manifest.yaml (mapping, planning)"));
  EXPECT_TRUE(mentions(p, "steps[0].kill: planner: not a module of manifest.yaml (mapping, planning)"))
      << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "steps[0].expect[0].back: planner"));
  EXPECT_TRUE(mentions(p, "starts no plant to apply it"));
  EXPECT_TRUE(checkAgainstModules(s, {"planner", "plant", "sim"}, {"planning", "plant", "plant"}).empty());

  // A datagram fault's sender is a participant, named after its module's kind.
  const Scenario d = parse(R"(
manifest: manifest.yaml
steps:
  - {at: 1, dds: {module: planner, from: planner, loss: 0.1}}
)");
  const auto q = checkAgainstModules(d, {"planner", "mapper"}, {"planning", "mapping"});
  EXPECT_TRUE(mentions(q, "steps[0].dds.from: planner: no module of manifest.yaml sends as 'planner'"))
      << ::testing::PrintToString(q);
  EXPECT_EQ(q.size(), 1U);
}

TEST_F(ScenarioFiles, AStepOnAModuleThatSharesItsProcessIsRefusedInTheComposedLayout)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
steps:
  - {at: 1, kill: planning}
  - {at: 2, dds: {module: control, loss: 0.1}}
  - {at: 3, pause: display}
  - {at: 4, plant: {kind: wind_gust, wind: [3, 0, 0], duration: 1}, expect: [{rejected: control, within: 2}]}
)");
  // The composed layout of a manifest: {mapping, planning} and {plant, control} a process
  // each, the display alone.
  launch::Manifest m;
  launch::Module slow{.name = "slow", .kind = launch::kContainerKind};
  slow.hosted = {launch::Module{.name = "mapping", .kind = "mapping"}, launch::Module{.name = "planning", .kind = "planning"}};
  launch::Module fast{.name = "fast", .kind = launch::kContainerKind};
  fast.hosted = {launch::Module{.name = "plant", .kind = "plant"}, launch::Module{.name = "control", .kind = "control"}};
  m.modules = {slow, launch::Module{.name = "display", .kind = "display"}, fast};
  const auto p = checkAgainstContainers(s, m);
  EXPECT_TRUE(mentions(p, "steps[0].kill: planning: shares process slow with mapping in the composed layout: a fault "
                          "on it alone needs the distributed layout"))
      << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "steps[1].dds.module: control: shares process fast with plant"));
  EXPECT_FALSE(mentions(p, "steps[2]")) << "the display is a process of its own";
  EXPECT_FALSE(mentions(p, "steps[3]")) << "a plant fault, and each node counts what it refuses";
  EXPECT_EQ(p.size(), 2U) << ::testing::PrintToString(p);
  // Distributed, nothing to refuse.
  launch::Manifest apart;
  for (const char* name : {"mapping", "planning", "plant", "control", "display"}) {
    apart.modules.push_back(launch::Module{.name = name, .kind = name});
  }
  EXPECT_TRUE(checkAgainstContainers(s, apart).empty());
}

TEST_F(ScenarioFiles, AFleetsWatchedVehicleAndEachVehiclesOutcomeAreReadAndChecked)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
vehicle: 2
steps:
  - {at: 1, kill: planning.2}
outcome: {mission: failure, vehicles: {1: success, 2: failure, 3: any}}
)");
  EXPECT_EQ(s.vehicle, 2U);
  EXPECT_EQ(s.outcome.mission, Outcome::Mission::kFailure);
  ASSERT_EQ(s.outcome.vehicles.size(), 3U);
  EXPECT_EQ(s.outcome.vehicles.at(1), Outcome::Mission::kSuccess);
  EXPECT_EQ(s.outcome.vehicles.at(2), Outcome::Mission::kFailure);
  EXPECT_EQ(s.outcome.vehicles.at(3), Outcome::Mission::kAny);
  EXPECT_TRUE(checkAgainstVehicles(s, {1, 2, 3}, true).empty());
  auto p = checkAgainstVehicles(s, {1, 2}, true);
  ASSERT_EQ(p.size(), 1U);
  EXPECT_TRUE(mentions(p, "outcome.vehicles.3: 3: not a vehicle of manifest.yaml (1, 2)")) << p[0];
  p = checkAgainstVehicles(s, {0}, false);
  EXPECT_EQ(p.size(), 4U);
  EXPECT_TRUE(mentions(p, "vehicle: 2: manifest.yaml flies one vehicle, not a fleet")) << ::testing::PrintToString(p);

  const auto q = problems(R"(
manifest: manifest.yaml
vehicle: 1.5
steps: [{at: 1, kill: planning}]
outcome: {vehicles: {2: landed}}
)");
  EXPECT_TRUE(mentions(q, "vehicle: 1.5: expected a vehicle id (a whole number)")) << ::testing::PrintToString(q);
  EXPECT_TRUE(mentions(q, "outcome.vehicles.2: landed: expected success, failure, crashed or any"));
}

constexpr std::int64_t kMs = 1'000'000;

Scenario killScenario()
{
  Scenario s;
  s.name = "k";
  Step kill;
  kill.at_s = 5.0;
  kill.action.kind = Action::Kind::kKill;
  kill.action.module = "planning";
  kill.expect = {{Expectation::Kind::kNoticed, "", "planning", 0.6},
                 {Expectation::Kind::kMode, "HOVER", "", 1.5},
                 {Expectation::Kind::kBack, "", "planning", 3.0}};
  s.steps.push_back(kill);
  s.outcome.zero_loss = false;
  return s;
}

RunFacts goodRun()
{
  RunFacts f;
  f.mission_known = true;
  f.mission_success = true;
  f.mission_outcome = "landed at the goal";
  f.actuator_commands = 100;
  return f;
}

TEST(Judge, ReactionsAreMeasuredFromWhenTheFaultTookEffect)
{
  const Scenario s = killScenario();
  Judge j(s);
  j.mode(1.0, "MISSION");
  EXPECT_TRUE(j.due(4.9).empty());
  const auto due = j.due(5.02);
  ASSERT_EQ(due.size(), 1U);
  EXPECT_TRUE(j.due(5.1).empty());  // handed out once
  j.applied(0, 5.02, 1000 * kMs, "SIGKILL to pid 7");
  j.lost("planning", 1480 * kMs);
  j.clock(6.0, 2000 * kMs);
  j.mode(6.12, "HOVER");
  EXPECT_FALSE(j.settled());
  j.back("planning", 2500 * kMs);
  EXPECT_TRUE(j.settled());
  const auto rows = j.finish(goodRun());
  EXPECT_TRUE(passed(rows)) << toTable("k", rows);
  const std::string table = toTable("k", rows);
  EXPECT_NE(table.find("at 5.02 s: SIGKILL to pid 7"), std::string::npos) << table;
  EXPECT_NE(table.find("0.480 s"), std::string::npos) << table;  // noticed
  EXPECT_NE(table.find("1.100 s"), std::string::npos) << table;  // HOVER
  EXPECT_NE(table.find("1.500 s"), std::string::npos) << table;  // back
  EXPECT_NE(table.find("scenario k: PASS"), std::string::npos) << table;
  // The same verdict for programs (fault_report.json), with each reaction's time and bound.
  const auto json = nlohmann::json::parse(toJson("k", rows));
  EXPECT_EQ(json["scenario"], "k");
  EXPECT_EQ(json["passed"], true);
  ASSERT_EQ(json["rows"].size(), rows.size());
  int timed = 0;
  for (const auto& r : json["rows"]) {
    if (!r["measured_s"].is_null()) {
      EXPECT_LE(r["measured_s"].get<double>(), r["within_s"].get<double>()) << r;
      ++timed;
    }
  }
  EXPECT_EQ(timed, 3) << json.dump(2);  // noticed 0.48 s, HOVER 1.1 s, back 1.5 s
}

TEST(Judge, LateOrMissingReactionsAndABadOutcomeFail)
{
  const Scenario s = killScenario();
  Judge j(s);
  ASSERT_EQ(j.due(5.0).size(), 1U);
  j.applied(0, 5.0, 0, "SIGKILL to pid 7");
  j.lost("planning", 900 * kMs);  // too late
  j.mode(7.0, "HOVER");           // too late
  j.clock(9.0, 4000 * kMs);       // and never back
  EXPECT_TRUE(j.settled());
  RunFacts f = goodRun();
  f.collisions = 1;
  f.nonfinite_actuator_commands = 3;
  const auto rows = j.finish(f);
  EXPECT_FALSE(passed(rows));
  int failed = 0;
  for (const auto& r : rows) {
    failed += r.pass ? 0 : 1;
  }
  EXPECT_EQ(failed, 5) << toTable("k", rows);  // noticed, mode, back, collisions, actuators
  EXPECT_NE(toTable("k", rows).find("0.900 s"), std::string::npos);
}

/// The kill scenario's fault applied and every reaction in time.
void reactInTime(Judge& j)
{
  j.applied(0, 5.0, 0, "SIGKILL to pid 7");
  j.lost("planning", 100 * kMs);
  j.mode(5.5, "HOVER");
  j.back("planning", 2000 * kMs);
}

TEST(Judge, ACrashedOutcomeWantsTheMissionEndedCrashedNotJustFailed)
{
  Scenario s = killScenario();
  s.outcome.mission = Outcome::Mission::kCrashed;
  Judge j(s);
  reactInTime(j);
  RunFacts f = goodRun();
  f.mission_success = false;
  f.mission_end = "failed";
  f.mission_outcome = "landed short of the goal";
  EXPECT_FALSE(passed(j.finish(f))) << toTable("k", j.finish(f));
  f.mission_end = "crashed";
  f.mission_outcome = "crashed into obstacle 0 at 7.24 m/s";
  EXPECT_TRUE(passed(j.finish(f))) << toTable("k", j.finish(f));
}

TEST(Judge, EachVehicleOfAFleetIsHeldToItsOwnOutcome)
{
  Scenario s = killScenario();
  s.outcome.mission = Outcome::Mission::kFailure;
  s.outcome.vehicles = {{1, Outcome::Mission::kSuccess}, {2, Outcome::Mission::kFailure}, {3, Outcome::Mission::kSuccess}};
  Judge j(s);
  reactInTime(j);
  RunFacts f = goodRun();
  f.mission_success = false;
  f.vehicle_missions = {{1, {true, "landed at the goal"}}, {2, {true, "landed at the goal"}}};
  const auto rows = j.finish(f);
  const std::string table = toTable("k", rows);
  // Vehicle 2 should have failed; vehicle 3 flew no mission at all.
  int failed = 0;
  for (const auto& r : rows) {
    failed += r.pass ? 0 : 1;
  }
  EXPECT_EQ(failed, 2) << table;
  EXPECT_NE(table.find("vehicle 2's mission fails"), std::string::npos) << table;
  EXPECT_NE(table.find("vehicle 3's mission succeeds"), std::string::npos) << table;
  EXPECT_NE(table.find("no mission"), std::string::npos) << table;
  f.vehicle_missions[2] = {false, "landed short of the goal"};
  f.vehicle_missions[3] = {true, "landed at the goal"};
  // With every vehicle as the scenario says, the same reactions pass.
  Judge k(s);
  k.applied(0, 5.0, 0, "SIGKILL to pid 7");
  k.lost("planning", 100 * kMs);
  k.mode(5.5, "HOVER");
  k.back("planning", 2000 * kMs);
  const auto good = k.finish(f);
  EXPECT_TRUE(passed(good)) << toTable("k", good);
}

TEST(Judge, AModeAlreadyHeldWhenTheFaultTakesEffectIsMetAtOnce)
{
  Scenario s = killScenario();
  s.steps[0].expect = {{Expectation::Kind::kMode, "HOVER", "", 0.5}};
  Judge j(s);
  j.mode(3.0, "HOVER");
  ASSERT_EQ(j.due(5.0).size(), 1U);
  j.applied(0, 5.0, 0, "x");
  EXPECT_TRUE(j.settled());
  EXPECT_TRUE(passed(j.finish(goodRun())));
}

TEST(Judge, OutliersAreMeasuredInSimTimeFromTheFaultAndOnlyAfterIt)
{
  Scenario s = killScenario();
  s.steps[0].expect = {{Expectation::Kind::kOutliers, "", "position", 0.3}};
  Judge j(s);
  ASSERT_EQ(j.due(5.0).size(), 1U);
  j.applied(0, 5.0, 0, "x");
  j.outliers("position", 4.9);  // a false alarm before the fault is no reaction to it
  j.outliers("mag", 5.05);      // another sensor's
  EXPECT_FALSE(j.settled());
  j.outliers("position", 5.15);
  EXPECT_TRUE(j.settled());
  const auto rows = j.finish(goodRun());
  EXPECT_TRUE(passed(rows)) << toTable("o", rows);
  EXPECT_NE(toTable("o", rows).find("0.150 s"), std::string::npos) << toTable("o", rows);
  Judge late(s);
  ASSERT_EQ(late.due(5.0).size(), 1U);
  late.applied(0, 5.0, 0, "x");
  late.clock(5.4, 0);
  EXPECT_FALSE(passed(late.finish(goodRun())));
}

TEST(Judge, AModeAfterTheLastPathIsMeasuredFromThatPathsStamp)
{
  // Path timeout 1 s: HOVER within 1.1 s of the last path is within 0.1 s of its going stale.
  Scenario s = killScenario();
  s.steps[0].expect = {{Expectation::Kind::kMode, "HOVER", "", 1.1, Expectation::Since::kLastPath}};
  Judge in_time(s);
  in_time.path(4.6);
  in_time.path(4.8);
  in_time.path(4.7);  // out of order: the newest counts
  ASSERT_EQ(in_time.due(5.0).size(), 1U);
  in_time.applied(0, 5.0, 0, "SIGKILL to pid 7");
  in_time.clock(5.85, 900 * kMs);
  in_time.mode(5.85, "HOVER");
  const auto rows = in_time.finish(goodRun());
  EXPECT_TRUE(passed(rows)) << toTable("k", rows);
  EXPECT_NE(toTable("k", rows).find("1.050 s"), std::string::npos) << toTable("k", rows);
  EXPECT_NE(toTable("k", rows).find("mode HOVER after the last path"), std::string::npos);

  Judge late(s);
  late.path(4.8);
  ASSERT_EQ(late.due(5.0).size(), 1U);
  late.applied(0, 5.0, 0, "SIGKILL to pid 7");
  late.mode(6.0, "HOVER");  // 1.2 s after the last path, though 1.0 s after the kill
  EXPECT_FALSE(passed(late.finish(goodRun())));

  Judge never(s);
  never.path(4.8);
  ASSERT_EQ(never.due(5.0).size(), 1U);
  never.applied(0, 5.0, 0, "SIGKILL to pid 7");
  never.clock(5.95, 950 * kMs);  // the bound is over at 5.9
  EXPECT_TRUE(never.settled());
  EXPECT_FALSE(passed(never.finish(goodRun())));
}

TEST(Judge, AltitudeLostIsTheDeepestDropBelowTheAltitudeAtTheFaultInItsWindow)
{
  Scenario s = killScenario();
  s.steps[0].expect = {{Expectation::Kind::kAltitudeLost, "", "", 3.0, Expectation::Since::kFault, 0.5}};
  const auto fly = [&](const std::vector<std::pair<double, double>>& track) {
    Judge j(s);
    j.altitude(4.0, 9.0);  // before the fault: not its reference
    EXPECT_EQ(j.due(5.0).size(), 1U);
    j.applied(0, 5.0, 0, "SIGKILL to pid 7");
    for (const auto& [t, z] : track) {
      j.altitude(t, z);
      j.clock(t, 0);
    }
    EXPECT_TRUE(j.settled());
    return j.finish(goodRun());
  };
  // Down 0.4 m and back up, then a drop after the window (not counted).
  const auto held = fly({{5.0, 2.0}, {5.5, 1.8}, {6.0, 1.6}, {7.0, 2.1}, {8.0, 2.0}, {8.2, 0.2}});
  EXPECT_TRUE(passed(held)) << toTable("k", held);
  EXPECT_NE(toTable("k", held).find("0.40 m"), std::string::npos) << toTable("k", held);
  EXPECT_NE(toTable("k", held).find("<= 0.50 m in 3.00 s (sim)"), std::string::npos) << toTable("k", held);
  // Falls 0.7 m: failed as soon as it is below the bound.
  const auto fell = fly({{5.0, 2.0}, {5.3, 1.3}, {5.4, 1.9}, {8.1, 2.0}});
  EXPECT_FALSE(passed(fell));
  EXPECT_NE(toTable("k", fell).find("0.70 m by 0.30 s"), std::string::npos) << toTable("k", fell);
  // No state after the fault: nothing to judge by, a failure.
  Judge j(s);
  ASSERT_EQ(j.due(5.0).size(), 1U);
  j.applied(0, 5.0, 0, "SIGKILL to pid 7");
  j.clock(8.5, 0);
  EXPECT_FALSE(passed(j.finish(goodRun())));
}

TEST(Judge, ARefusedOrUnreachedStepFailsWithItsReason)
{
  Scenario s = killScenario();
  Step second = s.steps[0];
  second.at_s = 50.0;
  s.steps.push_back(second);
  Judge j(s);
  ASSERT_EQ(j.due(5.0).size(), 1U);
  j.refused(0, "planning is not running");
  j.clock(20.0, 0);
  const auto rows = j.finish(goodRun());
  const std::string table = toTable("k", rows);
  EXPECT_NE(table.find("refused: planning is not running"), std::string::npos) << table;
  EXPECT_NE(table.find("not reached (the run ended at 20.00 s)"), std::string::npos) << table;
  EXPECT_FALSE(passed(rows));
}

TEST(Judge, RecordingLossAndAnUnreadableRecordingFail)
{
  Scenario s = killScenario();
  s.steps.clear();
  s.outcome.zero_loss = true;
  RunFacts f = goodRun();
  f.reliable_loss = {{"quad/mapping/update", 0}, {"quad/planning/path", 2}};
  f.module_loss = {{"planning", 0}, {"control", 0}};
  EXPECT_FALSE(passed(Judge(s).finish(f)));
  f.reliable_loss["quad/planning/path"] = 0;
  EXPECT_TRUE(passed(Judge(s).finish(f)));
  // What the modules' own readers lost counts as much as what the recorder lost.
  f.module_loss["control"] = 4;
  const auto rows = Judge(s).finish(f);
  EXPECT_FALSE(passed(rows));
  EXPECT_NE(toTable("k", rows).find("control 4"), std::string::npos) << toTable("k", rows);
  f.module_loss["control"] = 0;
  f.recording_problem = "log/x.mcap: no loss figures";
  EXPECT_FALSE(passed(Judge(s).finish(f)));
}

Scenario linkScenario(std::optional<double> duration)
{
  Scenario s;
  s.name = "l";
  Step st;
  st.at_s = 2.0;
  st.action.kind = Action::Kind::kDds;
  st.action.module = "planning";
  st.action.datagrams = {{1001, wire::DatagramFaultKind::kLoss, 0.2, "mapping", 7}};
  st.action.duration_s = duration;
  s.steps.push_back(st);
  s.outcome.zero_loss = false;
  return s;
}

TEST(Judge, ADatagramFaultMustBeAcknowledgedAsClearedWithWhatItDid)
{
  const Scenario s = linkScenario(60.0);
  Judge j(s);
  ASSERT_EQ(j.due(2.0).size(), 1U);
  j.applied(0, 2.0, 0, "acknowledged by planning");
  EXPECT_TRUE(j.isApplied(0));
  auto rows = j.finish(goodRun());
  EXPECT_FALSE(passed(rows));
  EXPECT_NE(toTable("l", rows).find("not acknowledged"), std::string::npos) << toTable("l", rows);
  j.cleared(0, 62.0, "planning: datagram fault 1001 cleared: it acted on 20 of 100 datagrams");
  rows = j.finish(goodRun());
  EXPECT_TRUE(passed(rows)) << toTable("l", rows);
  EXPECT_NE(toTable("l", rows).find("at 62.00 s: planning: datagram fault 1001 cleared"), std::string::npos);
  // Without a duration it lasts until the run ends.
  const Scenario open = linkScenario(std::nullopt);
  Judge k(open);
  k.due(2.0);
  k.applied(0, 2.0, 0, "acknowledged by planning");
  k.cleared(0, 30.0, "x");
  EXPECT_NE(toTable("l", k.finish(goodRun())).find("at the end"), std::string::npos);
}

}  // namespace
}  // namespace quad::fault
