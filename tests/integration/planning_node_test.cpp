// SPDX-License-Identifier: BSD-3-Clause
// The planning node as a process: a goal and the vehicle's state in, a path out; in a lockstep
// run with the plant and the mapper, its paths due a budget after their states.
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "json_lines.hpp"
#include "module_wait.hpp"
#include "process.hpp"
#include "wait.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

TEST(PlanningNode, PlansFromTheVehicleToTheGoalAndRefusesGoalsOutsideTheBounds)
{
  const int domain = 165;
  ChildProcess planning({QUAD_PLANNING_NODE, "--config", std::string(QUAD_CONFIG_DIR) + "/planning.yaml"}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "planning", 20s)) << planning.output();
  ChildProcess goal({QUAD_TOOL, "topic", "pub", "quad/planning/goal",
                     "{goal_id: 1, p_W: {x: 10, y: 2, z: 2}, tolerance: 0.3}", "--wait-match", "5"},
                    env(domain));
  ASSERT_EQ(goal.wait(15s), 0) << goal.output();
  ChildProcess path({QUAD_TOOL, "topic", "echo", "quad/planning/path", "-n", "1", "--timeout", "20"}, env(domain));
  ChildProcess state({QUAD_TOOL, "topic", "pub", "quad/estimation/state",
                      "{p_W: {x: 0, y: 0, z: 2}, q_WB: {w: 1}, aligned: true}", "--count", "20", "--rate", "5"},
                     env(domain));
  ASSERT_EQ(path.wait(25s), 0) << path.output() << planning.output();
  EXPECT_NE(path.output().find("status: PLAN_OK"), std::string::npos) << path.output();
  EXPECT_NE(path.output().find("goal_id: 1"), std::string::npos) << path.output();
  // Unknown space is traversable: the way is straight, so two waypoints remain.
  EXPECT_NE(path.output().find("waypoints_W:\n  - x: 0.0\n"), std::string::npos) << path.output();
  ChildProcess far({QUAD_TOOL, "topic", "pub", "quad/planning/goal",
                    "{goal_id: 2, p_W: {x: 500, y: 0, z: 2}, tolerance: 0.3}"},
                   env(domain));
  EXPECT_EQ(far.wait(15s), 0) << far.output();
  // The refusal counts as an error in the planner's heartbeat, and the path stays goal 1's.
  EXPECT_TRUE(quad::test::waitForModuleErrors(domain, "planning", 1, 20s)) << planning.output();
  ChildProcess still({QUAD_TOOL, "topic", "echo", "quad/planning/path", "-n", "1", "--timeout", "10", "--json"},
                     env(domain));
  ASSERT_EQ(still.wait(15s), 0) << still.output();
  const auto paths = quad::test::jsonLines(still.output());
  ASSERT_EQ(paths.size(), 1U) << still.output();
  EXPECT_EQ(paths.front()["goal_id"], 1) << still.output();
  EXPECT_EQ(paths.front()["status"], "PLAN_OK") << still.output();
}

/// The newest sample of the run's clock, as `quad topic echo` prints it.
std::int64_t clockNs(const std::map<std::string, std::string>& run_env)
{
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "-n", "1", "--json", "--timeout", "10"}, run_env);
  EXPECT_EQ(echo.wait(20s), 0) << echo.output();
  const auto samples = quad::test::jsonLines(echo.output());
  return samples.empty() ? -1 : samples.front()["sim_ns"].get<std::int64_t>();
}

/// The paths a planner published through a 30 s run (JSON lines) end with a path from the
/// run's last seconds: it planned on to the end.
void expectPlannedToTheEnd(const std::string& paths)
{
  const auto heard = quad::test::jsonLines(paths);
  ASSERT_FALSE(heard.empty());
  EXPECT_EQ(heard.back()["status"], "PLAN_OK") << heard.back();
  EXPECT_GT(heard.back()["header"]["stamp_ns"].get<std::int64_t>(), 25'000'000'000) << heard.back();
}

/// The plant in lockstep for 30 s of sim time with the mapper and the planner, and a
/// controller that holds 2 m over the start, everyone on the plant's true state (no
/// estimator runs here), on `run_env`'s domain; the plant starts with start().
struct LockstepStack {
  LockstepStack(const std::map<std::string, std::string>& run_env, const std::string& name)
      : env(run_env),
        dir(prepared(name)),
        mapping({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, env),
        // One state read per 20 ms: a planner done with a period's state is done with the
        // period, whatever its budget (the next test's 4 ms is shorter than the period).
        planning({QUAD_PLANNING_NODE, "--config", std::string(QUAD_CONFIG_DIR) + "/planning.yaml", "--set",
                  "state.source=truth", "--set", "state.rate=50"},
                 env),
        controller({QUAD_ALTITUDE_CONTROLLER, "757.5", "2.0"}, env)
  {
  }
  ~LockstepStack() { std::filesystem::remove_all(dir); }

  /// A fresh folder `name` with the mapper's and the plant's configs.
  static std::filesystem::path prepared(const std::string& name)
  {
    const auto dir = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "mapping.yaml") << "state: {source: truth}\n";
    std::ofstream(dir / "plant.yaml") << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\nworld: "
                                      << QUAD_CONFIG_DIR << "/worlds/demo.yaml\n"
                                      << "sim: {mode: lockstep, duration: 30}\nlockstep: {participants: "
                                         "'mapping,planning'}\nstate: {source: truth}\n";
    return dir;
  }
  /// The modules are up, and the planner has goal 1 at (10, 0, 2), stamped at sim time 0.
  void ready(int domain)
  {
    ASSERT_TRUE(quad::test::waitForRunningModule(domain, "mapping", 20s)) << mapping.output();
    ASSERT_TRUE(quad::test::waitForRunningModule(domain, "planning", 20s)) << planning.output();
    ASSERT_TRUE(controller.waitForOutput("ready", 10s)) << controller.output();
    ChildProcess goal({QUAD_TOOL, "topic", "pub", "quad/planning/goal",
                       "{header: {stamp_ns: 0}, goal_id: 1, p_W: {x: 10, y: 0, z: 2}, tolerance: 0.3}", "--wait-match",
                       "5"},
                      env);
    ASSERT_EQ(goal.wait(15s), 0) << goal.output();
  }
  void start() { plant.emplace(std::vector<std::string>{QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, env); }
  /// Stops the mapper and the planner, which must end cleanly.
  void stop()
  {
    planning.signal(SIGTERM);
    mapping.signal(SIGTERM);
    EXPECT_EQ(planning.wait(10s), 0) << planning.output();
    EXPECT_EQ(mapping.wait(10s), 0) << mapping.output();
  }

  std::map<std::string, std::string> env;
  std::filesystem::path dir;
  ChildProcess mapping;
  ChildProcess planning;
  ChildProcess controller;
  std::optional<ChildProcess> plant;
};

// In lockstep a path is due the planner's budget of sim time after the vehicle state it was
// planned on, stamped with that time, and starts where the vehicle will be then; the clock runs
// on while the planner works, stands where its promise ends while it is stopped, and a path
// out after the clock reached its due time counts as an overrun.
TEST(PlanningNode, InLockstepAPathIsDueTheBudgetAfterItsStateAndTheClockStandsForAStoppedPlanner)
{
  // One step of the plant: the clock is at the due time of a replan as soon as the planner
  // has its state, so the planner overruns.
  constexpr std::int64_t kBudgetNs = 4'000'000;
  auto run_env = env(87);
  run_env["QUAD_PATH_BUDGET_MS"] = "4";
  run_env["QUAD_LOCKSTEP"] = "1";
  run_env["QUAD_PARTICIPANT_LEASE"] = "10";  // peers keep a stopped participant
  LockstepStack stack(run_env, "quad_planning_node_budget_test");
  stack.ready(87);
  if (::testing::Test::HasFatalFailure()) {
    return;
  }
  ChildProcess paths({QUAD_TOOL, "topic", "echo", "quad/planning/path", "-n", "40", "--json", "--timeout", "120"},
                     run_env);
  // Every state, into a file: a pipe nobody reads while the test waits would stall the echo,
  // and its reader would drop what comes meanwhile.
  const auto states_file = stack.dir / "states.jsonl";
  ChildProcess states({"/bin/sh", "-c",
                       std::string("exec ") + QUAD_TOOL + " topic echo quad/sim/state --json > " + states_file.string()},
                      run_env);  // until stopped
  ASSERT_TRUE(quad::test::waitForReader(87, "quad/planning/path", 15s));
  std::this_thread::sleep_for(1s);  // the states' echo matched (the mapper's and the planner's readers tell nothing)
  stack.start();
  ChildProcess& plant = *stack.plant;
  // GIVEN a lockstep run of 30 s, its planner past its fifth path
  ASSERT_TRUE(quad::test::waitFor([&] { return quad::test::newestReached(paths.output(), "version", 5); }, 60s))
      << paths.output() << plant.output();
  // WHEN the planner is stopped for a few seconds
  stack.planning.signal(SIGSTOP);
  std::this_thread::sleep_for(1500ms);
  const std::int64_t held_ns = clockNs(run_env);
  std::this_thread::sleep_for(1500ms);
  const std::int64_t still_ns = clockNs(run_env);
  stack.planning.signal(SIGCONT);
  ASSERT_EQ(plant.wait(90s), 0) << plant.output();
  ASSERT_EQ(paths.wait(30s), 0) << paths.output();
  states.signal(SIGINT);
  ASSERT_EQ(states.wait(10s), 0);

  // THEN the clock stood short of the run's end while the planner was stopped
  EXPECT_GT(held_ns, 0);
  EXPECT_EQ(still_ns, held_ns);
  EXPECT_LT(held_ns, 30'000'000'000);
  // AND each path is stamped the budget after a vehicle state and starts where the vehicle
  // would be by then at that state's velocity (checked on the states the best-effort echo
  // caught)
  std::map<std::int64_t, nlohmann::json> state_at;
  std::stringstream caught;
  caught << std::ifstream(states_file).rdbuf();
  for (const auto& s : quad::test::jsonLines(caught.str())) {
    state_at[s["header"]["stamp_ns"].get<std::int64_t>()] = s;
  }
  const auto component = [](const nlohmann::json& v, const char* axis) { return v[axis].get<double>(); };
  int checked = 0;
  std::uint64_t overruns = 0;
  for (const auto& p : quad::test::jsonLines(paths.output())) {
    const std::int64_t planned_ns = p["header"]["stamp_ns"].get<std::int64_t>() - kBudgetNs;
    EXPECT_GE(p["overruns"].get<std::uint64_t>(), overruns) << p;  // counted since the start
    overruns = p["overruns"].get<std::uint64_t>();
    const auto state = state_at.find(planned_ns);
    if (p["waypoints_W"].empty() || state == state_at.end()) {
      continue;
    }
    for (const char* axis : {"x", "y", "z"}) {
      const double expected = component(state->second["p_W"], axis) +
                              component(state->second["v_W"], axis) * static_cast<double>(kBudgetNs) * 1e-9;
      EXPECT_NEAR(component(p["waypoints_W"].front(), axis), expected, 1e-12) << axis << " " << p << state->second;
    }
    ++checked;
  }
  EXPECT_GE(checked, 10) << paths.output();
  // AND the clock reached the due time of a path before it was out: an overrun
  EXPECT_GE(overruns, 1U) << paths.output();
  stack.stop();
}

/// GIVEN a lockstep run of 30 s on `domain`, its planner past its third path, WHEN `sample`
/// comes on `topic` (a map output damaged on the way), THEN the planner counts it as an error
/// AND plans on to the run's end.
void expectRefusedAndPlannedOn(int domain, const std::string& name, const std::string& topic, const std::string& sample)
{
  auto run_env = env(domain);
  run_env["QUAD_LOCKSTEP"] = "1";
  LockstepStack stack(run_env, name);
  stack.ready(domain);
  if (::testing::Test::HasFatalFailure()) {
    return;
  }
  ChildProcess paths({QUAD_TOOL, "topic", "echo", "quad/planning/path", "--json"}, run_env);  // until stopped
  ASSERT_TRUE(quad::test::waitForReader(domain, "quad/planning/path", 15s));
  stack.start();
  ASSERT_TRUE(quad::test::waitFor([&] { return quad::test::newestReached(paths.output(), "version", 3); }, 60s))
      << paths.output() << stack.plant->output();
  ChildProcess bad({QUAD_TOOL, "topic", "pub", topic, sample, "--wait-match", "5"}, run_env);
  ASSERT_EQ(bad.wait(15s), 0) << bad.output();
  EXPECT_TRUE(quad::test::waitForModuleErrors(domain, "planning", 1, 20s)) << stack.planning.output();
  ASSERT_EQ(stack.plant->wait(90s), 0) << stack.plant->output();
  paths.signal(SIGINT);
  ASSERT_EQ(paths.wait(10s), 0);
  expectPlannedToTheEnd(paths.output());
  stack.stop();
}

// A map update that counts depth frames the clock never reached (one bit flipped on a link
// did so, 2^31 frames) is refused as a bad input: held until the clock got there, it would
// hold every later update back, and the planner would never plan again.
TEST(PlanningNode, InLockstepAnUpdateCountingFramesPastTheClockIsRefusedAndPlanningGoesOn)
{
  expectRefusedAndPlannedOn(88, "quad_planning_node_bad_update_test", "quad/mapping/update",
                            "{update_seq: 1000000, resolution: 0.2, depth_frames: 2147483648}");
}

// A map snapshot stamped far past the clock (2^62 ns: a bit flipped in its stamp) is refused
// as a bad input once the mapper's next one comes (within a second of sim time) stamped before
// it: held until the clock got there, it would hold every later snapshot back, and a planner
// with a gap in its updates would never fill it.
TEST(PlanningNode, InLockstepASnapshotStampedPastTheNextIsRefusedAndPlanningGoesOn)
{
  expectRefusedAndPlannedOn(215, "quad_planning_node_bad_snapshot_test", "quad/mapping/octomap",
                            "{header: {stamp_ns: 4611686018427387904}, update_seq: 1000000, resolution: 0.2}");
}

// A map update whose count of depth frames was damaged upwards by less than the clock's lead
// passes that check, but counts more frames than the updates after it (the mapper's counts
// never fall). Held until the clock got there, it held the updates after it back, and the
// lockstep clock stood for good with the planner waiting for them; it is refused instead.
TEST(PlanningNode, InLockstepAnUpdateCountingMoreFramesThanTheNextIsRefusedAndTheClockGoesOn)
{
  auto run_env = env(189);
  run_env["QUAD_LOCKSTEP"] = "1";
  run_env["QUAD_PARTICIPANT_LEASE"] = "10";  // peers keep the stopped plant
  LockstepStack stack(run_env, "quad_planning_node_falling_count_test");
  stack.ready(189);
  if (::testing::Test::HasFatalFailure()) {
    return;
  }
  ChildProcess paths({QUAD_TOOL, "topic", "echo", "quad/planning/path", "--json"}, run_env);  // until stopped
  // Every clock sample, into a file (a stopped plant answers no new reader's discovery)
  const auto clock_file = stack.dir / "clock.jsonl";
  ChildProcess clock({"/bin/sh", "-c",
                      std::string("exec ") + QUAD_TOOL + " topic echo quad/sim/clock --json > " + clock_file.string()},
                     run_env);  // until stopped
  ASSERT_TRUE(quad::test::waitForReader(189, "quad/planning/path", 15s));
  std::this_thread::sleep_for(1s);  // the clock's echo matched
  stack.start();
  // GIVEN a lockstep run of 30 s, its planner past its third path, the plant stopped there
  ASSERT_TRUE(quad::test::waitFor([&] { return quad::test::newestReached(paths.output(), "version", 3); }, 60s))
      << paths.output() << stack.plant->output();
  stack.plant->signal(SIGSTOP);
  std::this_thread::sleep_for(500ms);
  std::stringstream heard_clock;
  heard_clock << std::ifstream(clock_file).rdbuf();
  const auto clocks = quad::test::jsonLines(heard_clock.str());
  ASSERT_FALSE(clocks.empty());
  const auto frames = clocks.back()["depth_frames"].get<std::uint64_t>();
  // WHEN an update comes that counts ten depth frames more than the clock (within its lead),
  // and the mapper's next, counting fewer, after it
  ChildProcess bad({QUAD_TOOL, "topic", "pub", "quad/mapping/update",
                    "{update_seq: 1000000, resolution: 0.2, depth_frames: " + std::to_string(frames + 10) + "}",
                    "--wait-match", "5"},
                   run_env);
  ASSERT_EQ(bad.wait(15s), 0) << bad.output();
  std::this_thread::sleep_for(500ms);
  stack.plant->signal(SIGCONT);
  // THEN the planner counts it as an error
  EXPECT_TRUE(quad::test::waitForModuleErrors(189, "planning", 1, 20s)) << stack.planning.output();
  // AND the clock goes on to the run's end, the planner planning on to its last seconds
  ASSERT_EQ(stack.plant->wait(90s), 0) << stack.plant->output() << stack.planning.output();
  paths.signal(SIGINT);
  ASSERT_EQ(paths.wait(10s), 0);
  clock.signal(SIGINT);
  ASSERT_EQ(clock.wait(10s), 0);
  expectPlannedToTheEnd(paths.output());
  stack.stop();
}

TEST(PlanningNode, ARepublishPeriodReadersWouldCallStaleIsRefusedNamingTheKey)
{
  // The quad/planning/path contract's deadline is 1 s: a repeat every 0.8 s is too slow.
  ChildProcess planning({QUAD_PLANNING_NODE, "--config", std::string(QUAD_CONFIG_DIR) + "/planning.yaml", "--set",
                         "republish_period=0.8"},
                        env(166));
  EXPECT_NE(planning.wait(15s), 0) << planning.output();
  EXPECT_NE(planning.output().find("republish_period: 0.8: above half the quad/planning/path deadline (1 s)"),
            std::string::npos)
      << planning.output();
}

}  // namespace
