// SPDX-License-Identifier: BSD-3-Clause
// The mapping node in a lockstep run with the plant: it takes part in lockstep, publishes
// change sets and stats, and saves a map OctoMap reads.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <csignal>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "module_wait.hpp"
#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}, {"QUAD_TRANSPORT", "udp"}};
}

/// A plant config in `dir`: the x500 in the demo world, lockstep with the mapper for `seconds`.
/// No estimator runs here: the mapper places the clouds on the plant's true state.
void writePlantConfig(const std::filesystem::path& dir, double seconds)
{
  std::ofstream(dir / "plant.yaml") << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\nworld: "
                                    << QUAD_CONFIG_DIR << "/worlds/demo.yaml\n"
                                    << "sim: {mode: lockstep, duration: " << seconds
                                    << "}\nlockstep: {participants: mapping}\nstate: {source: truth}\n";
}

TEST(MappingNode, LockstepRunMapsTheBoxAndSavesABtFile)
{
  const int domain = 160;
  const auto dir = std::filesystem::temp_directory_path() / "quad_mapping_node_test";
  std::filesystem::create_directories(dir);
  const auto bt = dir / "map.bt";
  std::filesystem::remove(bt);
  std::ofstream(dir / "mapping.yaml") << "save_path: " << bt.string() << "\nstate: {source: truth}\n";
  writePlantConfig(dir, 3.0);
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

// A mapper stopped and started again with the same checkpoint file publishes, before any
// scan, the very map the first one had, numbered past every update the first one sent.
TEST(MappingNode, AMapperStartedAgainResumesFromItsCheckpoint)
{
  const int domain = 122;
  const auto dir = std::filesystem::temp_directory_path() / "quad_mapping_node_resume_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto bt = dir / "map.bt";
  std::ofstream(dir / "mapping.yaml") << "state: {source: truth}\nsave_path: " << bt.string() << "\ncheckpoint: {file: "
                                      << (dir / "mapping.checkpoint").string() << "}\n";
  writePlantConfig(dir, 2.0);
  // GIVEN a mapper that mapped 2 s of flight and stopped
  {
    ChildProcess mapping({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, env(domain));
    ChildProcess controller({QUAD_ALTITUDE_CONTROLLER, "757.5", "2.0"}, env(domain));
    ASSERT_TRUE(quad::test::waitForRunningModule(domain, "mapping", 20s)) << mapping.output();
    ASSERT_TRUE(controller.waitForOutput("ready", 10s)) << controller.output();
    ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, env(domain));
    ASSERT_EQ(plant.wait(90s), 0) << plant.output();
    mapping.signal(SIGTERM);
    ASSERT_EQ(mapping.wait(10s), 0) << mapping.output();
  }
  octomap::OcTree saved(bt.string());
  ASSERT_GT(saved.size(), 1000U);
  // WHEN one is started again with the same checkpoint file, and no camera
  ChildProcess again({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, env(domain));
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/mapping/octomap", "-n", "1", "--json", "--max-elements",
                     "100000000", "--timeout", "30"},
                    env(domain));
  ASSERT_EQ(echo.wait(40s), 0) << echo.output() << again.output();
  // THEN its snapshot holds the map the first one saved, voxel for voxel
  const auto sample = nlohmann::json::parse(echo.output());
  EXPECT_GE(sample["update_seq"].get<std::uint64_t>(), 1'000'000U);  // past the reservation
  EXPECT_GT(sample["header"]["stamp_ns"].get<std::int64_t>(), 1'500'000'000);  // scans of the 2 s
  const auto bytes = sample["octree"].get<std::vector<std::uint8_t>>();
  std::istringstream in(std::string(bytes.begin(), bytes.end()));
  octomap::OcTree resumed(0.2);
  ASSERT_TRUE(resumed.readBinary(in));
  ASSERT_EQ(resumed.size(), saved.size());
  std::size_t compared = 0;
  for (auto it = saved.begin_leafs(); it != saved.end_leafs(); ++it, ++compared) {
    const octomap::OcTreeNode* n = resumed.search(it.getKey(), static_cast<unsigned>(it.getDepth()));
    ASSERT_NE(n, nullptr);
    ASSERT_EQ(resumed.isNodeOccupied(n), saved.isNodeOccupied(*it));
  }
  EXPECT_GT(compared, 100U);
  again.signal(SIGTERM);
  EXPECT_EQ(again.wait(10s), 0) << again.output();
  std::filesystem::remove_all(dir);
}

}  // namespace
