// The plant and control nodes flying together: the loop the stack is built around.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "process.hpp"

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

TEST(Flight, LockstepMissionReachesItsGoalWithoutCollision)
{
  const int domain = 150;
  const std::string plant_config =
      writeFile("plant.yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR + "/vehicles/x500.yaml\nworld: " +
                                  QUAD_CONFIG_DIR + "/worlds/open.yaml\nsim: {mode: lockstep, duration: 25.0}\n");
  // The operator's path comes at a wall-clock rate, while lockstep sim time runs many times
  // faster: path staleness (tested in the core) is judged in sim time, so give it room here.
  const std::string control_config =
      writeFile("control.yaml", std::string("vehicle: ") + QUAD_CONFIG_DIR +
                                    "/vehicles/x500.yaml\nautostart: true\nmodes: {auto_mission: true}\n"
                                    "timeouts: {path: 600}\n");
  // GIVEN the control node (autostart, auto mission) and an operator's goal and path, which
  // the operator vouches is free all along (known_free_m: the controller flies no further)
  ChildProcess control({QUAD_CONTROL_NODE, "--config", control_config}, env(domain));
  ASSERT_TRUE(control.waitForOutput("running on domain", 10s)) << control.output();
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
  // WHEN the plant runs 25 s of lockstep sim time
  ChildProcess plant({QUAD_PLANT_NODE, "--config", plant_config}, env(domain));
  ASSERT_EQ(plant.wait(90s), 0) << plant.output();
  // THEN the vehicle took off, flew the mission, reached the goal, and hit nothing
  EXPECT_TRUE(control.waitForOutput("MISSION -> HOVER: goal reached", 5s)) << control.output();
  EXPECT_NE(plant.output().find("collisions 0,"), std::string::npos) << plant.output();
  std::smatch m;
  const std::string out = plant.output();
  ASSERT_TRUE(std::regex_search(out, m, std::regex("final state t [0-9]+ ns p \\(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\\)")))
      << out;
  EXPECT_NEAR(std::stod(m[1]), 20.0, 0.3);
  EXPECT_NEAR(std::stod(m[2]), 5.0, 0.3);
  EXPECT_NEAR(std::stod(m[3]), 3.0, 0.3);
}

}  // namespace
