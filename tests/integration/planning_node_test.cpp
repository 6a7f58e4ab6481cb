// SPDX-License-Identifier: BSD-3-Clause
// The planning node as a process: a goal and the vehicle's state in, a path out.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

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
