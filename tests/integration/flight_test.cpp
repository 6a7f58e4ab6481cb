// SPDX-License-Identifier: BSD-3-Clause
// The plant and control nodes flying together: the loop the stack is built around, here on
// the plant's ground truth (the shipped manifests add the estimator between them).
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

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

std::string writeFile(const std::string& name, const std::string& body)
{
  const auto dir = std::filesystem::temp_directory_path() / "quad_flight_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << body;
  return path.string();
}

/// The samples a `quad topic echo --json` printed, one JSON object a line.
TEST(Flight, LockstepMissionReachesItsGoalWithoutCollision)
{
  const int domain = 150;
  const std::string plant_config =
      writeFile("plant.yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nworld: " +
                                  QUAD_CONFIG_DIR + "/worlds/open.yaml\nsim: {mode: lockstep, duration: 25.0}\n"
                                  "state: {source: truth}\n");
  // The operator's path comes at a wall-clock rate, while lockstep sim time runs many times
  // faster: path staleness (tested in the core) is judged in sim time, so give it room here.
  const std::string control_config =
      writeFile("control.yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR +
                                    "/vehicles/x500.yaml\nautostart: true\nmodes: {auto_mission: true}\n"
                                    "timeouts: {path: 600}\nstate: {source: truth}\n");
  // GIVEN the control node (autostart, auto mission) and an operator's goal and path, which
  // the operator vouches is free all along (known_free_m: the controller flies no further)
  ChildProcess control({QUAD_CONTROL_NODE, "--config", control_config}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "control", 20s)) << control.output();
  ChildProcess goal({QUAD_TOOL, "topic", "pub", "quad/planning/goal",
                     "{goal_id: 1, p_W: {x: 20, y: 5, z: 3}, tolerance: 0.3}", "--wait-match", "5"},
                    env(domain));
  ChildProcess path({QUAD_TOOL, "topic", "pub", "quad/planning/path",
                     "{version: 1, goal_id: 1, status: PLAN_OK, waypoints_W: [{x: 0, y: 0, z: 2}, "
                     "{x: 10, y: 0, z: 2}, {x: 20, y: 5, z: 3}], known_free_m: 1000}",
                     "--count", "100", "--rate", "2", "--wait-match", "5"},
                    env(domain));
  ASSERT_TRUE(goal.waitForOutput("published", 10s)) << goal.output();
  ASSERT_TRUE(path.waitForOutput("published", 10s)) << path.output();
  // AND readers of the plant's events (the run's end carries the final position and the
  // collision count) and of the controller's status
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, env(domain));
  ChildProcess status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json"}, env(domain));
  // WHEN the plant runs 25 s of lockstep sim time
  ChildProcess plant({QUAD_PLANT_NODE, "--config", plant_config}, env(domain));
  ASSERT_EQ(plant.wait(90s), 0) << plant.output();
  // THEN the vehicle took off, flew the mission, reached the goal, and hit nothing
  ASSERT_TRUE(events.waitForOutput("SIM_EVENT_RUN_ENDED", 10s)) << events.output();
  const std::vector<nlohmann::json> seen = quad::test::jsonLines(events.output());
  const auto kind = [&](const char* k) {
    return std::find_if(seen.begin(), seen.end(), [&](const nlohmann::json& e) { return e["kind"] == k; });
  };
  EXPECT_NE(kind("SIM_EVENT_TAKEOFF"), seen.end()) << events.output();
  const auto ended = kind("SIM_EVENT_RUN_ENDED");
  ASSERT_NE(ended, seen.end()) << events.output();
  EXPECT_EQ((*ended)["subject_id"], 0) << "collisions: " << *ended;
  EXPECT_NEAR((*ended)["p_W"]["x"].get<double>(), 20.0, 0.3) << *ended;
  EXPECT_NEAR((*ended)["p_W"]["y"].get<double>(), 5.0, 0.3) << *ended;
  EXPECT_NEAR((*ended)["p_W"]["z"].get<double>(), 3.0, 0.3) << *ended;
  // AND the controller went from the mission to hovering at the goal, with no failsafe (the
  // status reader may still be printing the run's last samples when the run has ended)
  nlohmann::json hover;
  const auto hoverAfterMission = [&] {
    const std::vector<nlohmann::json> modes = quad::test::jsonLines(status.output());
    const auto mission = std::find_if(modes.begin(), modes.end(),
                                      [](const nlohmann::json& m) { return m["mode"] == "CONTROL_MISSION"; });
    const auto found =
        std::find_if(mission, modes.end(), [](const nlohmann::json& m) { return m["mode"] == "CONTROL_HOVER"; });
    if (found != modes.end()) {
      hover = *found;
    }
    return found != modes.end();
  };
  ASSERT_TRUE(quad::test::waitFor(hoverAfterMission, 10s)) << status.output();
  EXPECT_EQ(hover["failsafe_reason"], "FAILSAFE_NONE") << hover;
}

}  // namespace

namespace {

/// The newest `header.stamp_ns` among the samples a `quad topic echo --json` printed; -1 if none.
std::int64_t lastStamp(const std::string& output)
{
  std::int64_t last = -1;
  for (const auto& s : quad::test::jsonLines(output)) {
    last = std::max(last, s["header"]["stamp_ns"].get<std::int64_t>());
  }
  return last;
}

TEST(Flight, InRealTimeTheStatesDeadlineEventReachesTheFailsafeBeforeTheControllersOwnTimer)
{
  const int domain = 61;
  const std::string plant_config =
      writeFile("plant_rt.yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nworld: " +
                                     QUAD_CONFIG_DIR + "/worlds/open.yaml\nsim: {mode: realtime, duration: 60.0}\n"
                                     "state: {source: truth}\n");
  const std::string control_config = writeFile(
      "control_rt.yaml",
      std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nautostart: true\nstate: {source: truth}\n");
  // GIVEN the plant in real time and the controller holding the vehicle after its take-off
  ChildProcess control({QUAD_CONTROL_NODE, "--config", control_config}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "control", 20s)) << control.output();
  ChildProcess status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json"}, env(domain));
  ChildProcess plant({QUAD_PLANT_NODE, "--config", plant_config}, env(domain));
  ASSERT_TRUE(status.waitForOutput("CONTROL_HOVER", 30s)) << status.output() << plant.output();
  // (the plant's clock: reliable, its newest sample always delivered, one per step, each step
  // with its state)
  ChildProcess clock({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "--json"}, env(domain));
  ASSERT_TRUE(clock.waitForOutput("sim_ns", 10s)) << clock.output();
  std::this_thread::sleep_for(1s);
  // WHEN the plant stops (SIGSTOP: no state, no IMU sample, no clock)
  plant.signal(SIGSTOP);
  // THEN the controller takes the state for stale (holding on the IMU's last samples, then
  // landing when they end too), judged on the state's last sim time plus the silence: the
  // state topic's DDS deadline (its contract's 0.1 s) fires at the timeout, while the
  // controller's own wall-clock tick would judge no sooner than 0.14 s (its 0.04 s backstop
  // past the timeout)
  ASSERT_TRUE(status.waitForOutput("CONTROL_FAILSAFE_LAND", 10s)) << status.output();
  std::this_thread::sleep_for(500ms);
  const std::int64_t last_state_ns = lastStamp(clock.output());
  nlohmann::json failsafe;
  for (const auto& s : quad::test::jsonLines(status.output())) {
    if (s["failsafe_reason"] == "FAILSAFE_STATE_STALE" && failsafe.is_null()) {
      failsafe = s;
    }
  }
  plant.signal(SIGCONT);
  ASSERT_FALSE(failsafe.is_null());
  EXPECT_EQ(failsafe["failsafe_reason"], "FAILSAFE_STATE_STALE") << failsafe;
  const double judged_after = static_cast<double>(failsafe["header"]["stamp_ns"].get<std::int64_t>() - last_state_ns) * 1e-9;
  // (the silence is measured from when the node took the last state, a little after the
  // middleware received it)
  EXPECT_GE(judged_after, 0.09) << failsafe;
  EXPECT_LT(judged_after, 0.13) << failsafe << "\nlast state at " << last_state_ns << " ns\n" << control.output();
}

}  // namespace
