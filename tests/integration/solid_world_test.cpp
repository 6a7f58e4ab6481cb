// SPDX-License-Identifier: BSD-3-Clause
// Real scanned places and a solid world (DDS domains 170 to 174): the indoor vehicle down the
// corridor of a laser-scanned office floor and through one of its doors, and the demo's vehicle
// from a platform onto a roof and up through a hole onto an upper floor. In lockstep with a
// fixed seed; each reads the run's summary and exit status, and `quad plan`'s optimum. And the
// scan as the display draws it, read from its scene topic.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "flight.hpp"
#include "quad/world/world_file.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

const std::string kSource = QUAD_SOURCE_DIR;

using quad::test::Flight;

/// Flies `manifest` (bringup/<manifest>.yaml) in configs/worlds/<world>.yaml on its own domain,
/// with the module settings `sets` (`--set MODULE:KEY=VALUE`).
Flight fly(const std::string& manifest, const std::string& world, int domain, const std::vector<std::string>& sets)
{
  std::vector<std::string> args{kSource + "/bringup/" + manifest + ".yaml", "--world",
                                kSource + "/configs/worlds/" + world + ".yaml", "--domain", std::to_string(domain)};
  for (const auto& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  return quad::test::flyMission(QUAD_TOOL, args, "quad_solid_" + world);
}

/// `quad plan --manifest`'s result for the world, as JSON.
nlohmann::json knownMapPlan(const std::string& manifest, const std::string& world)
{
  const fs::path dir = quad::test::scratchDir("quad_solid_plan_" + world);
  ChildProcess plan({QUAD_TOOL, "plan", "--manifest", kSource + "/bringup/" + manifest + ".yaml", "--world",
                     kSource + "/configs/worlds/" + world + ".yaml", "--json", (dir / "plan.json").string()});
  const auto status = plan.wait(60s);
  EXPECT_EQ(status, 0) << plan.output();
  auto j = nlohmann::json::parse(quad::test::readFile(dir / "plan.json"), nullptr, false);
  fs::remove_all(dir);
  return j;
}

/// Reached with no collision and landed, within 1.3 times quad plan's optimum (the summary's
/// is the same plan), `landed_below_goal` [m] under the goal: on what lies beneath it.
void expectLandedBeneathTheGoal(const std::string& manifest, const std::string& world, int domain,
                                double landed_below_goal, const std::vector<std::string>& sets = {})
{
  const nlohmann::json plan = knownMapPlan(manifest, world);
  ASSERT_EQ(plan["status"], "ok") << plan.dump(2);
  EXPECT_NEAR(plan["landing_m"].get<double>(), landed_below_goal, 1e-6) << plan.dump(2);
  const Flight f = fly(manifest, world, domain, sets);
  ASSERT_TRUE(f.summary.is_object()) << f.output;
  EXPECT_EQ(f.exit_status, 0) << f.summary.dump(2) << f.output;
  EXPECT_EQ(f.summary["end"], "success") << f.summary.dump(2);
  EXPECT_EQ(f.summary["collisions"], 0) << f.summary.dump(2);
  EXPECT_GT(f.summary["min_clearance_m"].get<double>(), 0.0) << f.summary.dump(2);
  EXPECT_NEAR(f.summary["optimum_m"].get<double>(), plan["optimum_m"].get<double>(), 1e-6) << f.summary.dump(2);
  EXPECT_LE(f.summary["flown_over_optimum"].get<double>(), 1.3) << f.summary.dump(2);
  // it rests on the surface beneath the goal: as far below it as that surface (the tolerance
  // is the mission's, 0.3-0.4 m, sideways)
  EXPECT_NEAR(f.summary["goal_distance_m"].get<double>(), landed_below_goal, 0.4) << f.summary.dump(2);
  EXPECT_GE(f.summary["goal_distance_m"].get<double>(), landed_below_goal - 0.05) << f.summary.dump(2);
}

TEST(SolidWorld, TheScannedOfficesCorridorIsFlownEndToEnd)
{
  expectLandedBeneathTheGoal("indoor", "geb079", 170, 1.0);  // the floor's top is at z = 0
}

TEST(SolidWorld, TheVehicleLeavesTheCorridorThroughADoorOfTheScan)
{
  expectLandedBeneathTheGoal("indoor", "geb079_door", 171, 1.2);
}

TEST(SolidWorld, TheVehicleTakesOffFromAPlatformAndLandsOnARoof)
{
  // The controller knows from the downward rangefinder that the vehicle stands on the platform,
  // 2 m up: it takes off from there rather than taking over in the air (docs/control.md).
  expectLandedBeneathTheGoal("demo", "platform_roof", 172, 1.5);  // the roof at 3 m, the goal at 4.5
}

TEST(SolidWorld, TheVehicleClimbsThroughAHoleAndLandsOnTheUpperFloor)
{
  expectLandedBeneathTheGoal("demo", "upper_floor", 173, 1.7);  // the slab's top at 5.3 m, the goal at 7
}

TEST(SolidWorld, TheDisplayDrawsTheScanAsBoxesHoldingEachOccupiedVoxelOnce)
{
  const std::string world_file = kSource + "/configs/worlds/geb079.yaml";
  const quad::world::World world = quad::world::loadWorld(world_file);
  ASSERT_EQ(world.maps().size(), 1u);
  const auto& map = world.maps()[0];
  const std::map<std::string, std::string> env{{"QUAD_DOMAIN_ID", "174"}, {"QUAD_TRANSPORT", "udp"}};
  ChildProcess display({QUAD_DISPLAY_NODE, "--set", "world=" + world_file}, env);
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/display/scene", "--domain", "174", "-n", "1", "--timeout", "60",
                     "--json", "--max-elements", "1000000"},
                    env);
  const auto status = echo.wait(90s);
  display.signal(SIGTERM);
  EXPECT_EQ(display.wait(10s), 0) << display.output();
  ASSERT_TRUE(status) << echo.output();
  ASSERT_EQ(*status, 0) << echo.output();
  const std::string out = echo.output();
  const auto scene = nlohmann::json::parse(out.substr(out.find('{')), nullptr, false);
  ASSERT_TRUE(scene.is_object()) << out.substr(0, 2000);
  // The world has no other obstacle: every cube is the scan's. Their volumes add up to the
  // occupied voxels' (the boxes do not overlap: unit.display.Scene.*), each within the scan's
  // box, and far fewer boxes than voxels.
  Eigen::Vector3d lo, hi;
  map.bounds(lo, hi);
  double volume = 0.0;
  std::size_t cubes = 0;
  for (const auto& entity : scene["entities"]) {
    for (const auto& cube : entity["cubes"]) {
      const Eigen::Vector3d c(cube["pose"]["position"]["x"].get<double>(), cube["pose"]["position"]["y"].get<double>(),
                              cube["pose"]["position"]["z"].get<double>());
      const Eigen::Vector3d size(cube["size"]["x"].get<double>(), cube["size"]["y"].get<double>(),
                                 cube["size"]["z"].get<double>());
      EXPECT_TRUE(((c - size / 2.0).array() >= lo.array() - 1e-6).all() && ((c + size / 2.0).array() <= hi.array() + 1e-6).all())
          << c.transpose() << " size " << size.transpose();
      volume += size.prod();
      ++cubes;
    }
  }
  const double voxel = std::pow(map.resolution(), 3);
  EXPECT_NEAR(volume / voxel, static_cast<double>(map.occupiedVoxels().size()), 1e-3);
  EXPECT_LT(cubes, map.occupiedVoxels().size() / 2);
}

}  // namespace
