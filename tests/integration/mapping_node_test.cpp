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

/// The newest sample of the run's clock, as `quad topic echo` prints it.
nlohmann::json clockSample(const std::map<std::string, std::string>& run_env)
{
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "-n", "1", "--json", "--timeout", "10"}, run_env);
  EXPECT_EQ(echo.wait(20s), 0) << echo.output();
  const auto samples = quad::test::jsonLines(echo.output());
  return samples.empty() ? nlohmann::json::object({{"sim_ns", -1}, {"depth_frames", 0}}) : samples.front();
}

// In lockstep a scan's outputs are due 50 ms of sim time after its depth frame and stamped
// with that time; the clock runs on while the mapper works, stands where the mapper's promise
// ends while it is stopped, and an update out after the clock reached its due time counts as
// an overrun.
TEST(MappingNode, AScansOutputsAreDueTheBudgetAfterItAndTheClockStandsForAStoppedMapper)
{
  constexpr std::int64_t kBudgetNs = 50'000'000;   // the map update's contract
  constexpr std::int64_t kFramePeriodNs = 100'000'000;  // the x500's 10 Hz camera
  const int domain = 83;
  // Peers keep a stopped participant for 10 s, not the 2 s that would drop the mapper.
  auto run_env = env(domain);
  run_env["QUAD_PARTICIPANT_LEASE"] = "10";
  const auto dir = std::filesystem::temp_directory_path() / "quad_mapping_node_budget_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "mapping.yaml") << "state: {source: truth}\n";
  writePlantConfig(dir, 30.0);
  ChildProcess mapping({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, run_env);
  ChildProcess controller({QUAD_ALTITUDE_CONTROLLER, "757.5", "2.0"}, run_env);
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "mapping", 20s)) << mapping.output();
  ASSERT_TRUE(controller.waitForOutput("ready", 10s)) << controller.output();
  // The updates (reliable: every one from the first this reader matched), and most of the
  // stats (best effort: a burst after the stop may lose a few) for the overruns they count.
  ChildProcess updates({QUAD_TOOL, "topic", "echo", "quad/mapping/update", "-n", "250", "--json", "--max-elements",
                        "1", "--timeout", "120"},
                       run_env);
  ChildProcess stats({QUAD_TOOL, "topic", "echo", "quad/mapping/stats", "-n", "200", "--json", "--timeout", "120"},
                     run_env);
  ASSERT_TRUE(quad::test::waitForReader(domain, "quad/mapping/update", 15s));
  ASSERT_TRUE(quad::test::waitForReader(domain, "quad/mapping/stats", 15s));
  ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, run_env);
  // GIVEN a lockstep run of 30 s past its tenth scan (the run may be over in a few seconds:
  // watched on the updates as they come, not on samples of the clock taken one by one)
  ASSERT_TRUE(quad::test::waitFor([&] { return quad::test::newestReached(updates.output(), "depth_frames", 10); }, 60s))
      << updates.output() << plant.output();
  // WHEN the mapper is stopped for a few seconds
  mapping.signal(SIGSTOP);
  std::this_thread::sleep_for(1500ms);
  const nlohmann::json held = clockSample(run_env);
  const auto out_before = quad::test::jsonLines(updates.output());  // scans out before the stop
  ASSERT_FALSE(out_before.empty()) << "no update by sim time 1 s";
  const std::int64_t first_not_out_ns = (out_before.back()["depth_frames"].get<std::int64_t>() + 1) * kFramePeriodNs;
  std::this_thread::sleep_for(1500ms);
  const nlohmann::json still = clockSample(run_env);
  mapping.signal(SIGCONT);
  ASSERT_EQ(plant.wait(90s), 0) << plant.output();
  ASSERT_EQ(updates.wait(30s), 0) << updates.output();
  ASSERT_EQ(stats.wait(30s), 0) << stats.output();

  // THEN the clock stood short of the run's end while the mapper was stopped
  const auto held_ns = held["sim_ns"].get<std::int64_t>();
  EXPECT_EQ(still["sim_ns"].get<std::int64_t>(), held_ns);
  EXPECT_LT(held_ns, 30'000'000'000);
  // AND every scan's update is stamped its frame's time (on the camera's 10 Hz grid) plus the
  // budget, one per frame in order, each frame once (however often a waiting plant resent it)
  const auto scans = quad::test::jsonLines(updates.output());
  ASSERT_EQ(scans.size(), 250U);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const auto frame = scans[i]["depth_frames"].get<std::int64_t>();
    EXPECT_EQ(scans[i]["header"]["stamp_ns"].get<std::int64_t>(), frame * kFramePeriodNs + kBudgetNs) << scans[i];
    if (i > 0) {
      EXPECT_EQ(frame, scans[i - 1]["depth_frames"].get<std::int64_t>() + 1) << scans[i];
    }
  }
  // AND the stats carry the same stamps, and the overruns, counted since the start, never go back
  const auto samples = quad::test::jsonLines(stats.output());
  ASSERT_EQ(samples.size(), 200U) << stats.output();
  std::uint64_t overruns = 0;
  for (const auto& sample : samples) {
    EXPECT_EQ(sample["header"]["stamp_ns"].get<std::int64_t>() % kFramePeriodNs, kBudgetNs) << sample;
    EXPECT_GE(sample["overruns"].get<std::uint64_t>(), overruns);
    overruns = sample["overruns"].get<std::uint64_t>();
  }
  // at most one a scan
  EXPECT_LE(static_cast<std::int64_t>(overruns),
            (samples.back()["header"]["stamp_ns"].get<std::int64_t>() - kBudgetNs) / kFramePeriodNs);
  // AND where the clock stood at or past the due time of the first scan not out at the stop,
  // the mapper, resumed, counted it as an overrun
  if (held_ns >= first_not_out_ns + kBudgetNs) {
    EXPECT_GE(overruns, 1U) << "the clock stood at " << held_ns << " ns; the first scan not out: " << first_not_out_ns;
  }
  mapping.signal(SIGTERM);
  EXPECT_EQ(mapping.wait(10s), 0) << mapping.output();
  std::filesystem::remove_all(dir);
}

// A mapper reading one state a period places a cloud that falls between two on the pose
// interpolated between them, once the later one came: within the map's budget when the period
// is no longer than it, and with every state read when it is (the budget 0: the clock stands at
// every frame until its update is out). A 15 Hz camera's frames fall off the states' grid.
TEST(MappingNode, CloudsBetweenTheStatesReadAreAllPlacedAndTheLockstepRunEnds)
{
  struct Case {
    int domain;
    const char* budget_ms;  // QUAD_MAP_BUDGET_MS; empty: the contract's 50 ms
    double state_rate;
  };
  for (const Case c : {Case{114, "", 20.0}, Case{115, "0", 50.0}}) {
    SCOPED_TRACE("budget " + std::string(c.budget_ms) + " ms, states at " + std::to_string(c.state_rate) + " Hz");
    auto run_env = env(c.domain);
    if (*c.budget_ms != '\0') {
      run_env["QUAD_MAP_BUDGET_MS"] = c.budget_ms;
    }
    const auto dir = std::filesystem::temp_directory_path() / ("quad_mapping_node_rate_test_" + std::to_string(c.domain));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "mapping.yaml") << "state: {source: truth, rate: " << c.state_rate << "}\n";
    writePlantConfig(dir, 3.0);
    std::ofstream(dir / "plant.yaml", std::ios::app) << "depth: {rate: 15.0}\n";
    // GIVEN a mapper reading states at the rate, and a controller holding the vehicle at 2 m
    ChildProcess mapping({QUAD_MAPPING_NODE, "--config", (dir / "mapping.yaml").string()}, run_env);
    ChildProcess controller({QUAD_ALTITUDE_CONTROLLER, "757.5", "2.0"}, run_env);
    ASSERT_TRUE(quad::test::waitForRunningModule(c.domain, "mapping", 20s)) << mapping.output();
    ASSERT_TRUE(controller.waitForOutput("ready", 10s)) << controller.output();
    ChildProcess stats({QUAD_TOOL, "topic", "echo", "quad/mapping/stats", "-n", "40", "--json", "--timeout", "120"},
                       run_env);
    ASSERT_TRUE(quad::test::waitForReader(c.domain, "quad/mapping/stats", 15s));
    // WHEN the plant runs 3 s of lockstep time with its camera at 15 Hz (45 frames)
    ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, run_env);
    // THEN the run ends (no frame's update waits for a state that never comes)
    ASSERT_EQ(plant.wait(30s), 0) << plant.output() << mapping.output();
    ASSERT_EQ(stats.wait(10s), 0) << stats.output();
    // AND every cloud was placed: none refused for want of a pose
    const auto samples = quad::test::jsonLines(stats.output());
    ASSERT_EQ(samples.size(), 40U) << stats.output();
    for (const auto& sample : samples) {
      EXPECT_EQ(sample["rejected_clouds"].get<std::uint64_t>(), 0U) << sample;
    }
    mapping.signal(SIGTERM);
    EXPECT_EQ(mapping.wait(10s), 0) << mapping.output();
    std::filesystem::remove_all(dir);
  }
}

// A state rate under which clouds could not be placed is refused, naming the key.
TEST(MappingNode, AStateRateTooLowToPlaceCloudsIsRefusedNamingTheKey)
{
  ChildProcess mapping({QUAD_MAPPING_NODE, "--config", std::string(QUAD_CONFIG_DIR) + "/mapping.yaml", "--set",
                        "state.rate=5"},
                       env(116));
  EXPECT_NE(mapping.wait(15s), 0) << mapping.output();
  EXPECT_NE(mapping.output().find("state.rate: 5: below 20 Hz"), std::string::npos) << mapping.output();
}

}  // namespace
