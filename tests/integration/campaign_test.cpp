// SPDX-License-Identifier: BSD-3-Clause
// quad campaign as a user runs it (DDS domains 93 and 100 to 103): worlds in turn, a sweep of
// a module's parameter flown two at a time against the same sweep flown one at a time, and a
// campaign stopped by a signal. Each reads the campaign's JSON and exit status.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

const std::string kWorlds = std::string(QUAD_SOURCE_DIR) + "/configs/worlds/";

nlohmann::json readJson(const fs::path& file)
{
  return nlohmann::json::parse(quad::test::readFile(file), nullptr, false);
}

/// The processes whose command line names `text` (the campaign's folder: its launchers and
/// their modules).
std::vector<std::string> processesNaming(const std::string& text)
{
  std::vector<std::string> found;
  for (const auto& proc : fs::directory_iterator("/proc")) {
    const std::string pid = proc.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    std::ifstream in(proc.path() / "cmdline");
    std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos) {
      found.push_back(pid + ": " + cmdline);
    }
  }
  return found;
}

TEST(Campaign, FliesEachWorldInTurnAndFailsWhenOneDoes)
{
  const fs::path dir = quad::test::scratchDir("quad_campaign");
  ChildProcess campaign({QUAD_TOOL, "campaign", kWorlds + "wall.yaml", kWorlds + "sealed.yaml", "--domain", "93",
                         "--log-dir", (dir / "runs").string(), "--json", (dir / "campaign.json").string()});
  const auto status = campaign.wait(600s);
  ASSERT_TRUE(status) << campaign.output();
  EXPECT_EQ(*status, 1) << campaign.output();  // the sealed goal fails the campaign
  const auto j = readJson(dir / "campaign.json");
  ASSERT_TRUE(j.is_object()) << campaign.output();
  ASSERT_EQ(j["runs"].size(), 2U) << j.dump(2);
  EXPECT_EQ(j["runs"][0]["world"], "wall");
  EXPECT_EQ(j["runs"][0]["success"], true) << j.dump(2);
  EXPECT_TRUE(j["runs"][0]["flown_over_optimum"].is_number()) << j.dump(2);
  EXPECT_EQ(j["runs"][1]["end"], "no_path") << j.dump(2);
  EXPECT_EQ(j["runs"][1]["exit_status"], 3) << j.dump(2);
  EXPECT_EQ(j["succeeded"], 1);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

/// A sweep of the follower's speed in the open world, `jobs` runs at a time.
nlohmann::json sweep(const fs::path& dir, int jobs, std::string& output)
{
  ChildProcess campaign({QUAD_TOOL, "campaign", kWorlds + "open.yaml", "--set", "control:follower.max_speed=2,4", "-j",
                         std::to_string(jobs), "--domain", "100", "--log-dir", dir.string()});
  const auto status = campaign.wait(600s);
  output = campaign.output();
  EXPECT_TRUE(status) << output;
  EXPECT_EQ(status.value_or(-1), 0) << output;
  return readJson(dir / "campaign.json");
}

TEST(Campaign, ASweepFlownTwoAtATimeFliesEachCellOnceAsOneAtATimeDoes)
{
  const fs::path dir = quad::test::scratchDir("quad_campaign_sweep");
  std::string parallel_output;
  std::string sequential_output;
  const auto parallel = sweep(dir / "parallel", 2, parallel_output);
  const auto sequential = sweep(dir / "sequential", 1, sequential_output);
  ASSERT_TRUE(parallel.is_object()) << parallel_output;
  ASSERT_TRUE(sequential.is_object()) << sequential_output;
  EXPECT_EQ(parallel["axes"], (nlohmann::json{{"control:follower.max_speed", {"2", "4"}}})) << parallel.dump(2);
  ASSERT_EQ(parallel["runs"].size(), 2U) << parallel.dump(2);
  ASSERT_EQ(sequential["runs"].size(), 2U) << sequential.dump(2);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& p = parallel["runs"][i];
    const auto& s = sequential["runs"][i];
    // each cell once, in the product's order, whichever ended first
    EXPECT_EQ(p["params"]["control:follower.max_speed"], i == 0 ? "2" : "4") << p.dump(2);
    EXPECT_EQ(p["name"], s["name"]);
    EXPECT_EQ(p["success"], true) << p.dump(2);
    // the axis's value reached the controller: the top speed keeps to it
    EXPECT_LE(p["top_speed_mps"].get<double>(), (i == 0 ? 2.0 : 4.0) * 1.05) << p.dump(2);
    EXPECT_GT(p["top_speed_mps"].get<double>(), (i == 0 ? 2.0 : 4.0) * 0.9) << p.dump(2);
    // the same flight as one at a time (lockstep, the same seed), and the same figures but
    // for the wall time: the observer judges each by its samples' stamps
    for (const auto& [key, value] : s.items()) {
      if (key != "wall_seconds" && key != "estimate_rms_m" && key != "estimate_nees") {
        EXPECT_EQ(p[key], value) << key << "\nparallel: " << p.dump(2) << "\nsequential: " << s.dump(2);
      }
    }
    // the estimate's score, to a pair of samples (a lockstep run's scoring is exact; a loaded
    // machine has been seen to leave the last pair out)
    for (const char* key : {"estimate_rms_m", "estimate_nees"}) {
      ASSERT_TRUE(p[key].is_number() && s[key].is_number()) << key << p.dump(2) << s.dump(2);
      EXPECT_NEAR(p[key].get<double>(), s[key].get<double>(), 0.01 * s[key].get<double>()) << key;
    }
  }
  // Two at a time, each on its own domain (100 and 101); one at a time, all on the first.
  const auto domainOf = [&](const char* kind, const nlohmann::json& run) {
    return readJson(dir / kind / run["name"].get<std::string>() / "run" / "run.json").value("domain", -1);
  };
  EXPECT_EQ(domainOf("parallel", parallel["runs"][0]), 100);
  EXPECT_EQ(domainOf("parallel", parallel["runs"][1]), 101);
  EXPECT_EQ(domainOf("sequential", sequential["runs"][1]), 100);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Campaign, ASignalStopsEveryRunAndLeavesNoProcessBehind)
{
  const fs::path dir = quad::test::scratchDir("quad_campaign_stop");
  ChildProcess campaign({QUAD_TOOL, "campaign", kWorlds + "long.yaml", kWorlds + "forest.yaml", kWorlds + "wall.yaml",
                         "-j", "2", "--domain", "102", "--log-dir", dir.string()});
  // Both runs flying: each launcher has written its run's record.
  const auto started = [&] {
    return fs::exists(dir / "long-seed1" / "run" / "run.json") && fs::exists(dir / "forest-seed1" / "run" / "run.json");
  };
  for (auto until = std::chrono::steady_clock::now() + 120s; !started() && std::chrono::steady_clock::now() < until;) {
    std::this_thread::sleep_for(200ms);
  }
  ASSERT_TRUE(started()) << campaign.output();
  std::this_thread::sleep_for(2s);
  campaign.signal(SIGINT);
  const auto status = campaign.wait(60s);
  ASSERT_TRUE(status) << campaign.output();
  EXPECT_EQ(*status, 128 + SIGINT) << campaign.output();
  EXPECT_EQ(processesNaming(dir.string()), std::vector<std::string>{}) << campaign.output();
  const auto j = readJson(dir / "campaign.json");
  ASSERT_TRUE(j.is_object()) << campaign.output();
  ASSERT_EQ(j["runs"].size(), 2U) << j.dump(2);  // the third never started
  for (const auto& r : j["runs"]) {
    EXPECT_EQ(r["end"], "interrupted") << j.dump(2);
  }
  EXPECT_FALSE(fs::exists(dir / "wall-seed1")) << j.dump(2);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
