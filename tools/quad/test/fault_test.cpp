// Fault scenarios: what a scenario file may say and the errors for what it may not, and the
// judge of a timeline: reaction times measured from when each fault took effect.
#include <gtest/gtest.h>

#include <fstream>

#include "fault/judge.hpp"
#include "fault/scenario.hpp"
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
steps:
  - at: 5
    kill: planning
    expect: [{noticed: planning, within: 0.6}, {mode: HOVER, within: 1.5}, {back: planning, within: 4}]
  - {at: 6, pause: mapping}
  - {at: 7, resume: mapping}
  - {at: 8, restart: control}
  - at: 9
    plant: {kind: motor, rotor: 2, efficiency: 0.5, duration: 3}
  - at: 10
    publish: {topic: quad/sim/state, values: {p_W: {x: .nan}}, count: 5, rate: 50}
    expect: [{rejected: control, within: 1}]
outcome: {mission: failure, collisions: 2, finite_actuators: false, recording_loss: any}
)");
  EXPECT_EQ(s.name, "all");
  EXPECT_EQ(s.mode, "realtime");
  ASSERT_EQ(s.steps.size(), 6U);
  EXPECT_EQ(s.steps[0].action.describe(), "kill planning");
  ASSERT_EQ(s.steps[0].expect.size(), 3U);
  EXPECT_EQ(s.steps[0].expect[1].describe(), "mode HOVER");
  EXPECT_TRUE(s.steps[0].expect[1].simTime());
  EXPECT_FALSE(s.steps[0].expect[0].simTime());
  EXPECT_EQ(s.steps[1].action.kind, Action::Kind::kPause);
  EXPECT_EQ(s.steps[3].action.kind, Action::Kind::kRestart);
  EXPECT_EQ(s.steps[4].action.kind, Action::Kind::kPlant);
  EXPECT_EQ(s.steps[4].action.plant.rotor, 2);
  EXPECT_EQ(s.steps[4].action.plant.id, 5U);  // the step's number
  EXPECT_EQ(s.steps[5].action.count, 5);
  EXPECT_DOUBLE_EQ(s.steps[5].action.rate_hz, 50.0);
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
steps:
  - {at: 5, kill: planning, pause: mapping}
  - {at: 4, explode: planning}
  - {at: 6, kill: planning, expect: [{mode: HOVERING, within: 1}]}
  - {at: 7, plant: {kind: motor, rotor: 7, efficiency: 0.5}}
  - {at: 8, publish: {topic: quad/sim/state, values: {nonsense: 1}}}
  - {at: -1, restart: control, expect: [{noticed: control}]}
outcome: {mission: maybe, colisions: 1}
)");
  EXPECT_TRUE(mentions(p, "s.yaml:manifest: nowhere.yaml: no such file")) << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "mode: sideways: expected realtime or lockstep"));
  EXPECT_TRUE(mentions(p, "one fault per step, found kill, pause"));
  EXPECT_TRUE(mentions(p, "steps[1].explode: planning: unknown fault"));
  EXPECT_TRUE(mentions(p, "steps[2].expect[0].mode: HOVERING: not a controller mode"));
  EXPECT_TRUE(mentions(p, "steps[3].plant.rotor: 7"));
  EXPECT_TRUE(mentions(p, "steps[4].publish.values: {nonsense: 1}: no field nonsense in VehicleState"));
  EXPECT_TRUE(mentions(p, "steps[5].at: -1"));
  EXPECT_TRUE(mentions(p, "steps[5].expect[0].within"));
  EXPECT_TRUE(mentions(p, "outcome.mission: maybe: expected success, failure or any"));
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

TEST_F(ScenarioFiles, ModulesAreCheckedAgainstTheManifest)
{
  const Scenario s = parse(R"(
manifest: manifest.yaml
steps:
  - {at: 1, kill: planner, expect: [{back: planner, within: 2}]}
  - {at: 2, plant: {kind: wind_gust, wind: [3, 0, 0], duration: 1}}
)");
  const auto p = checkAgainstModules(s, {"mapping", "planning"}, {"mapping", "planning"});
  EXPECT_TRUE(mentions(p, "steps[0].kill: planner: not a module of manifest.yaml (mapping, planning)"))
      << ::testing::PrintToString(p);
  EXPECT_TRUE(mentions(p, "steps[0].expect[0].back: planner"));
  EXPECT_TRUE(mentions(p, "starts no plant to apply it"));
  EXPECT_TRUE(checkAgainstModules(s, {"planner", "plant"}, {"planning", "plant"}).empty());
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
  EXPECT_FALSE(passed(Judge(s).finish(f)));
  f.reliable_loss["quad/planning/path"] = 0;
  EXPECT_TRUE(passed(Judge(s).finish(f)));
  f.recording_problem = "log/x.mcap: no loss figures";
  EXPECT_FALSE(passed(Judge(s).finish(f)));
}

}  // namespace
}  // namespace quad::fault
