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

/// A lockstep run's, as `quad launch` gives a lockstep manifest's modules: each node follows
/// lockstep's rules from its start, so an input it takes before the clock's first sample (the
/// battery and state of the first round, written ahead of it) is taken as it would be after.
std::map<std::string, std::string> lockstepEnv(int domain)
{
  auto e = env(domain);
  e["QUAD_LOCKSTEP"] = "1";
  return e;
}

std::string writeFile(const std::string& name, const std::string& body)
{
  const auto dir = std::filesystem::temp_directory_path() / "quad_flight_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << body;
  return path.string();
}

/// The control node (autostart, auto mission, on the plant's true state) with an operator's
/// goal at (20, 5, 3) and a path to it across the open world, which the operator vouches is free
/// all along (known_free_m: the controller flies no further), sent again twice a second, both
/// stamped at sim time 0 (in lockstep an operator's input takes effect at a sim time its stamp
/// fixes). The config files are named after the domain (tests run side by side).
struct OperatorMission {
  explicit OperatorMission(int domain)
      // The operator's path comes at a wall-clock rate, while lockstep sim time runs many times
      // faster: path staleness (tested in the core) is judged in sim time, so give it room here.
      : control({QUAD_CONTROL_NODE, "--config",
                 writeFile("control_" + std::to_string(domain) + ".yaml",
                           std::string("vehicle: ") + QUAD_CONFIG_DIR +
                               "/vehicles/x500.yaml\nautostart: true\nmodes: {auto_mission: true}\n"
                               "timeouts: {path: 600}\nstate: {source: truth}\n")},
                lockstepEnv(domain)),
        running(quad::test::waitForRunningModule(domain, "control", 20s)),
        goal({QUAD_TOOL, "topic", "pub", "quad/planning/goal",
              "{header: {stamp_ns: 0}, goal_id: 1, p_W: {x: 20, y: 5, z: 3}, tolerance: 0.3}", "--wait-match", "5"},
             lockstepEnv(domain)),
        path({QUAD_TOOL, "topic", "pub", "quad/planning/path",
              "{header: {stamp_ns: 0}, version: 1, goal_id: 1, status: PLAN_OK, waypoints_W: [{x: 0, y: 0, z: 2}, "
              "{x: 10, y: 0, z: 2}, {x: 20, y: 5, z: 3}], known_free_m: 1000}",
              "--count", "100", "--rate", "2", "--wait-match", "5"},
             lockstepEnv(domain))
  {
  }
  /// The controller runs, and the goal and the path are out.
  bool ready() { return running && goal.waitForOutput("published", 10s) && path.waitForOutput("published", 10s); }

  ChildProcess control;
  bool running;
  ChildProcess goal;
  ChildProcess path;
};

/// A lockstep plant config on the open world, with `extra` keys; named after `name`.
std::string lockstepOpenWorld(const std::string& name, double duration_s, const std::string& extra = "")
{
  return writeFile(name, std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nworld: " +
                             QUAD_CONFIG_DIR + "/worlds/open.yaml\nsim: {mode: lockstep, duration: " +
                             std::to_string(duration_s) + "}\nstate: {source: truth}\n" + extra);
}

TEST(Flight, LockstepMissionReachesItsGoalWithoutCollision)
{
  const int domain = 150;
  const std::string plant_config = lockstepOpenWorld("plant.yaml", 25.0);
  // GIVEN the control node (autostart, auto mission) and an operator's goal and path
  OperatorMission op(domain);
  ASSERT_TRUE(op.ready()) << op.control.output() << op.goal.output() << op.path.output();
  // AND readers of the plant's events (the run's end carries the final position and the
  // collision count) and of the controller's status
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, lockstepEnv(domain));
  ChildProcess status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json"}, lockstepEnv(domain));
  // WHEN the plant runs 25 s of lockstep sim time
  ChildProcess plant({QUAD_PLANT_NODE, "--config", plant_config}, lockstepEnv(domain));
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

namespace {

/// A lockstep flight on the plant's true state across the open world, whose state sensor drops
/// out for 1.5 s at 7 s of sim time (the plant's fault schedule, so at the same sim time in
/// every run): the plant's run's end (SIM_EVENT_RUN_ENDED) and the controller's statuses.
struct LockstepDropoutRun {
  nlohmann::json ended;
  std::vector<nlohmann::json> statuses;
};

LockstepDropoutRun lockstepDropoutRun(int domain)
{
  const std::string name = "dropout_" + std::to_string(domain);
  const std::string faults =
      writeFile(name + "_faults.yaml", "- {id: 1, kind: sensor_dropout, sensor: state, at: 7.0, duration: 1.5}\n");
  const std::string plant_config =
      lockstepOpenWorld(name + "_plant.yaml", 24.0, "faults: {schedule: " + faults + "}\n");
  OperatorMission op(domain);
  EXPECT_TRUE(op.ready()) << op.control.output() << op.goal.output() << op.path.output();
  ChildProcess events({QUAD_TOOL, "topic", "echo", "quad/sim/events", "--json"}, lockstepEnv(domain));
  ChildProcess status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json"}, lockstepEnv(domain));
  EXPECT_TRUE(quad::test::waitForReader(domain, "quad/sim/events", 15s));
  EXPECT_TRUE(quad::test::waitForReader(domain, "quad/control/status", 15s));
  ChildProcess plant({QUAD_PLANT_NODE, "--config", plant_config}, lockstepEnv(domain));
  EXPECT_EQ(plant.wait(90s), 0) << plant.output();
  LockstepDropoutRun run;
  EXPECT_TRUE(events.waitForOutput("SIM_EVENT_RUN_ENDED", 10s)) << events.output();
  for (const auto& e : quad::test::jsonLines(events.output())) {
    if (e["kind"] == "SIM_EVENT_RUN_ENDED") {
      run.ended = e;
    }
  }
  // (the echo prints all it has once stopped: its output is buffered)
  std::this_thread::sleep_for(1s);
  status.signal(SIGINT);
  status.wait(10s);
  run.statuses = quad::test::jsonLines(status.output());
  return run;
}

}  // namespace

// In lockstep a round whose state a fault dropped is answered too, on the IMU's dead reckoning
// at the clock's time, and the plant waits for that answer as for a state's: the vehicle is
// flown through the outage without lag, and two runs of it are the same run.
TEST(Flight, InLockstepAStateDropoutIsFlownOnDeadReckoningAndTwoRunsOfItAreBitIdentical)
{
  // GIVEN a lockstep mission at 2 m/s whose true state drops out for 1.5 s mid-flight
  // WHEN it is flown twice
  const LockstepDropoutRun a = lockstepDropoutRun(80);
  const LockstepDropoutRun b = lockstepDropoutRun(81);
  // THEN the controller held on its dead reckoning while the state was stale, and flew the
  // mission on once it was back
  ASSERT_FALSE(a.ended.is_null());
  ASSERT_FALSE(b.ended.is_null());
  const auto held = std::find_if(a.statuses.begin(), a.statuses.end(), [](const nlohmann::json& s) {
    return s["mode"] == "CONTROL_HOVER" && s["failsafe_reason"] == "FAILSAFE_STATE_STALE";
  });
  ASSERT_NE(held, a.statuses.end()) << a.statuses.size() << " statuses";
  EXPECT_NEAR((*held)["header"]["stamp_ns"].get<double>() * 1e-9, 7.1, 0.06) << *held;
  EXPECT_NE(std::find_if(held, a.statuses.end(), [](const nlohmann::json& s) { return s["mode"] == "CONTROL_MISSION"; }),
            a.statuses.end());
  // AND it hit nothing and reached the goal
  EXPECT_EQ(a.ended["subject_id"], 0) << "collisions: " << a.ended;
  EXPECT_NEAR(a.ended["p_W"]["x"].get<double>(), 20.0, 0.3) << a.ended;
  EXPECT_NEAR(a.ended["p_W"]["y"].get<double>(), 5.0, 0.3) << a.ended;
  // AND the two runs ended at the same sim time at the same position, to the last bit
  EXPECT_EQ(a.ended["header"]["stamp_ns"], b.ended["header"]["stamp_ns"]);
  EXPECT_EQ(a.ended["p_W"].dump(17), b.ended["p_W"].dump(17)) << a.ended << "\n" << b.ended;
}
