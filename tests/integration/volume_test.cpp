// SPDX-License-Identifier: BSD-3-Clause
// Flying the whole volume (DDS domains 145 to 149 91, 92 and 94): worlds that need a climb, a dip or a window, in lockstep with a
// fixed seed, and a goal that no path reaches. Each reads the run's summary and exit status.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "flight.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
using quad::test::Flight;
namespace fs = std::filesystem;

/// Flies the demo manifest in `world` (configs/worlds/<world>.yaml) on its own domain.
Flight fly(const std::string& world, int domain)
{
  return quad::test::flyMission(QUAD_TOOL,
                                {std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--world",
                                 std::string(QUAD_SOURCE_DIR) + "/configs/worlds/" + world + ".yaml", "--domain",
                                 std::to_string(domain)},
                                "quad_volume_" + world);
}

/// Reached with no collision, landed at the goal.
void expectReached(const std::string& world, int domain)
{
  const Flight f = fly(world, domain);
  ASSERT_TRUE(f.summary.is_object()) << f.output;
  EXPECT_EQ(f.exit_status, 0) << f.summary.dump(2) << f.output;
  EXPECT_EQ(f.summary["end"], "success") << f.summary.dump(2);
  EXPECT_EQ(f.summary["collisions"], 0) << f.summary.dump(2);
  EXPECT_GT(f.summary["min_clearance_m"].get<double>(), 0.0) << f.summary.dump(2);
  // flown no more than 1.3 times the known-map optimum (quad plan's, climb and landing included)
  ASSERT_TRUE(f.summary["flown_over_optimum"].is_number()) << f.summary.dump(2);
  EXPECT_LE(f.summary["flown_over_optimum"].get<double>(), 1.3) << f.summary.dump(2);
}

TEST(Volume, AWallAcrossTheBoxIsOverflown) { expectReached("wall", 145); }
TEST(Volume, AHighWindowOffTheAxisIsThreaded) { expectReached("window", 146); }
TEST(Volume, TheVehicleLeavesACourtyardOverItsWalls) { expectReached("courtyard", 147); }
TEST(Volume, GapsLowThenHighThenLowAreFlownThrough) { expectReached("gaps", 148); }
TEST(Volume, AnOverhangIsFlownUnder) { expectReached("overhang", 149); }

TEST(Volume, ASealedGoalEndsWithNoPathLandedAndNoCollision)
{
  const Flight f = fly("sealed", 91);
  ASSERT_TRUE(f.summary.is_object()) << f.output;
  EXPECT_EQ(f.exit_status, 3) << f.summary.dump(2) << f.output;  // docs/launch.md: no path
  EXPECT_EQ(f.summary["success"], false);
  EXPECT_EQ(f.summary["end"], "no_path") << f.summary.dump(2);
  EXPECT_NE(f.summary["failure"].get<std::string>(), "") << f.summary.dump(2);
  EXPECT_EQ(f.summary["collisions"], 0) << f.summary.dump(2);
  EXPECT_LT(f.summary["sim_seconds"].get<double>(), 150.0) << f.summary.dump(2);  // well before the timeout
}

TEST(Volume, AGoalInsideAnObstacleIsRefusedAtOnce)
{
  const fs::path dir = quad::test::scratchDir("quad_volume_refused");
  const fs::path world = dir / "w.yaml";
  std::ofstream(world) << "bounds: {min: [-5, -10, 0], max: [45, 10, 10]}\nstart: [0, 0, 0]\ngoal: [20, 0, 2]\n"
                          "obstacles:\n  - {type: box, center: [20, 0, 2], size: [2, 2, 4]}\n";
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--world",
                       world.string(), "--domain", "92", "--quiet", "--log-dir", (dir / "run").string()});
  const auto status = launch.wait(60s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 2) << launch.output();  // docs/launch.md: refused before anything started
  EXPECT_FALSE(fs::exists(dir / "run" / "plant.log")) << launch.output();
  fs::remove_all(dir);
}

TEST(Volume, AGoalOutsideTheGeofenceIsRefusedAtOnce)
{
  const fs::path dir = quad::test::scratchDir("quad_volume_fenced");
  const fs::path manifest = dir / "fenced.yaml";
  const std::string configs = std::string(QUAD_SOURCE_DIR) + "/configs/";
  // The demo's world and modules, fenced 10 m short of its goal (x = 50).
  std::ofstream(manifest) << "world: " << configs << "worlds/demo.yaml\n"
                          << "geofence: {min: [-5, -10, 0], max: [40, 10, 10]}\n"
                          << "modules:\n"
                          << "  plant: {config: " << configs << "plant.yaml, set: {world: \"${world}\"}}\n"
                          << "  planning: {config: " << configs << "planning.yaml, set: {world: \"${world}\"}}\n"
                          << "  control: {config: " << configs << "control.yaml}\n"
                          << "mission: {vehicle: " << configs << "vehicles/x500.yaml}\n";
  ChildProcess check({QUAD_TOOL, "launch", manifest.string(), "--check"});
  const auto valid = check.wait(30s);
  ASSERT_TRUE(valid) << check.output();
  ASSERT_EQ(*valid, 0) << check.output();  // a valid manifest: what follows is the goal's refusal
  ChildProcess launch({QUAD_TOOL, "launch", manifest.string(), "--domain", "94", "--quiet", "--log-dir",
                       (dir / "run").string()});
  const auto status = launch.wait(60s);
  ASSERT_TRUE(status) << launch.output();
  EXPECT_EQ(*status, 2) << launch.output();  // docs/launch.md: refused before anything started
  const auto run = nlohmann::json::parse(quad::test::readFile(dir / "run" / "run.json"), nullptr, false);
  ASSERT_TRUE(run.is_object()) << launch.output();
  EXPECT_EQ(run["exit_code"], 2) << run.dump(2);
  EXPECT_NE(run["failure"].get<std::string>().find("the goal (50, 0, 2) is outside the geofence"), std::string::npos)
      << run.dump(2);
  EXPECT_EQ(run["modules"]["plant"]["starts"], 0) << run.dump(2);
  fs::remove_all(dir);
}

}  // namespace
