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

/// The plant in real time, the controller holding the vehicle after its take-off on the
/// plant's true state, and `quad topic echo --json` of the controller's status and the clock.
/// Its config files are the domain's own (tests run side by side).
struct RealTimeHover {
  explicit RealTimeHover(int domain)
      : control({QUAD_CONTROL_NODE, "--config",
                 writeFile("control_rt_" + std::to_string(domain) + ".yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR +
                                                  "/vehicles/x500.yaml\nautostart: true\nstate: {source: truth}\n")},
                env(domain)),
        status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json"}, env(domain)),
        plant({QUAD_PLANT_NODE, "--config",
               writeFile("plant_rt_" + std::to_string(domain) + ".yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nworld: " +
                                              QUAD_CONFIG_DIR + "/worlds/open.yaml\nsim: {mode: realtime, duration: 60.0}\n"
                                              "state: {source: truth}\n")},
              env(domain)),
        clock({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "--json"}, env(domain))
  {
  }
  /// The first status that names `reason`, or null.
  nlohmann::json firstWith(const std::string& reason)
  {
    for (const auto& s : quad::test::jsonLines(status.output())) {
      if (s["failsafe_reason"] == reason) {
        return s;
      }
    }
    return nullptr;
  }

  ChildProcess control;
  ChildProcess status;
  ChildProcess plant;
  ChildProcess clock;  // reliable, its newest sample always delivered, one per step
};

TEST(Flight, InRealTimeAStalledPlantSlowsItsClockAndNoStateGoesStale)
{
  // GIVEN the plant in real time and the controller holding the vehicle after its take-off
  RealTimeHover run(61);
  ASSERT_TRUE(run.status.waitForOutput("CONTROL_HOVER", 30s)) << run.status.output() << run.plant.output();
  ASSERT_TRUE(run.clock.waitForOutput("sim_ns", 10s)) << run.clock.output();
  std::this_thread::sleep_for(1s);
  // WHEN the whole simulator stops for a second (SIGSTOP: no state, no IMU sample, no clock),
  // as a starved one does, and goes on
  run.plant.signal(SIGSTOP);
  std::this_thread::sleep_for(200ms);
  const std::int64_t stopped_at = lastStamp(run.clock.output());
  std::this_thread::sleep_for(800ms);
  run.plant.signal(SIGCONT);
  ASSERT_TRUE(quad::test::waitFor([&] { return lastStamp(run.clock.output()) > stopped_at + 500'000'000; }, 5s))
      << run.clock.output().substr(0, 2000);
  // THEN the vehicle's time stood still with it: the clock went on from where it stopped, the
  // lost second not flown in a burst, and nothing went stale in it: no failsafe, still holding
  std::int64_t after = -1;
  for (const auto& c : quad::test::jsonLines(run.clock.output())) {
    const auto t = c["header"]["stamp_ns"].get<std::int64_t>();
    if (t > stopped_at && after < 0) {
      after = t;
    }
  }
  EXPECT_LT(after - stopped_at, 50'000'000) << "the clock jumped from " << stopped_at << " to " << after;
  EXPECT_TRUE(run.firstWith("FAILSAFE_STATE_STALE").is_null()) << run.firstWith("FAILSAFE_STATE_STALE");
  const auto statuses = quad::test::jsonLines(run.status.output());
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.back()["mode"], "CONTROL_HOVER") << statuses.back();
  EXPECT_EQ(statuses.back()["failsafe_reason"], "FAILSAFE_NONE") << statuses.back();
}

TEST(Flight, InRealTimeStatesThatStopWhileTheClockRunsGoStaleAtTheirDeadline)
{
  // GIVEN the plant in real time and the controller holding the vehicle after its take-off
  RealTimeHover run(62);
  ASSERT_TRUE(run.status.waitForOutput("CONTROL_HOVER", 30s)) << run.status.output() << run.plant.output();
  ASSERT_TRUE(run.clock.waitForOutput("sim_ns", 10s)) << run.clock.output();
  ChildProcess states({QUAD_TOOL, "topic", "echo", "quad/sim/state", "--json"}, env(62));
  ASSERT_TRUE(states.waitForOutput("stamp_ns", 10s)) << states.output();
  std::this_thread::sleep_for(1s);
  // WHEN the plant's state sensor drops out for a second while the plant, and its clock, run on
  ChildProcess fault({QUAD_TOOL, "topic", "pub", "quad/system/fault",
                      "{fault_id: 1, module_name: plant, kind: FAULT_SENSOR_DROPOUT, target: state, index: -1, "
                      "magnitude: 0, duration_s: 1.0, seed: 1}",
                      "--wait-match", "5"},
                     env(62));
  EXPECT_EQ(fault.wait(10s), 0) << fault.output();
  // THEN the controller takes the state for stale at its deadline (the contract's 0.1 s), in
  // the clock's time from the last state
  ASSERT_TRUE(quad::test::waitFor([&] { return !run.firstWith("FAILSAFE_STATE_STALE").is_null(); }, 5s))
      << run.status.output();
  const nlohmann::json failsafe = run.firstWith("FAILSAFE_STATE_STALE");
  const std::int64_t judged_ns = failsafe["header"]["stamp_ns"].get<std::int64_t>();
  // (the echo's output is buffered: the states before the outage are all printed once the
  // states after it have pushed them out)
  ASSERT_TRUE(quad::test::waitFor([&] { return lastStamp(states.output()) > judged_ns + 1'500'000'000; }, 10s))
      << states.output().substr(0, 1000);
  std::int64_t last_state_ns = -1;
  for (const auto& s : quad::test::jsonLines(states.output())) {
    const auto t = s["header"]["stamp_ns"].get<std::int64_t>();
    if (t < judged_ns) {
      last_state_ns = std::max(last_state_ns, t);
    }
  }
  const double judged_after = static_cast<double>(judged_ns - last_state_ns) * 1e-9;
  EXPECT_GE(judged_after, 0.09) << failsafe;
  EXPECT_LT(judged_after, 0.13) << failsafe << "\nlast state at " << last_state_ns << " ns\n" << run.control.output();
}

}  // namespace
