// SPDX-License-Identifier: BSD-3-Clause
// The mapping node in a lockstep run with the plant: it takes part in lockstep, publishes
// change sets and stats, and saves a map OctoMap reads.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <csignal>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "module_wait.hpp"
#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

TEST(MappingNode, LockstepRunMapsTheBoxAndSavesABtFile)
{
  const int domain = 160;
  const auto dir = std::filesystem::temp_directory_path() / "quad_mapping_node_test";
  std::filesystem::create_directories(dir);
  const auto bt = dir / "map.bt";
  std::filesystem::remove(bt);
  std::ofstream(dir / "mapping.yaml") << "save_path: " << bt.string() << "\n";
  std::ofstream(dir / "plant.yaml") << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\nworld: "
                                    << QUAD_CONFIG_DIR << "/worlds/demo.yaml\n"
                                    << "sim: {mode: lockstep, duration: 3.0}\nlockstep: {participants: mapping}\n";
  // GIVEN a mapper, and a controller holding the vehicle at 2 m
  ChildProcess mapping({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, env(domain));
  ChildProcess controller({QUAD_ALTITUDE_CONTROLLER, "757.5", "2.0"}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "mapping", 20s)) << mapping.output();
  ASSERT_TRUE(controller.waitForOutput("ready", 10s)) << controller.output();
  ChildProcess stats({QUAD_TOOL, "topic", "echo", "quad/mapping/stats", "-n", "1", "--timeout", "30"}, env(domain));
  // WHEN the plant runs 3 s of lockstep time, waiting for the mapper at every round
  ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, env(domain));
  ASSERT_EQ(plant.wait(90s), 0) << plant.output();
  // THEN stats were published, and on shutdown the map is saved as a .bt OctoMap reads
  EXPECT_EQ(stats.wait(10s), 0) << stats.output();
  EXPECT_NE(stats.output().find("changed_voxels:"), std::string::npos) << stats.output();
  mapping.signal(SIGTERM);
  EXPECT_EQ(mapping.wait(10s), 0) << mapping.output();
  EXPECT_NE(mapping.output().find("map saved to"), std::string::npos) << mapping.output();
  octomap::OcTree tree(bt.string());
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.2);
  EXPECT_GT(tree.size(), 1000U);
}

}  // namespace
