// SPDX-License-Identifier: BSD-3-Clause
// Campaign summaries read back, tabled and written as JSON.
#include "quad/campaign/campaign.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "scratch.hpp"

namespace quad::campaign {
namespace {

namespace fs = std::filesystem;

fs::path writeSummary(const fs::path& dir, const std::string& name, const std::string& text)
{
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

TEST(Campaign, ASummaryIsReadBackWithItsOptimumAndEnd)
{
  const fs::path dir = test::scratchDir("quad_campaign_read");
  const auto file = writeSummary(dir, "a.json", R"({"success": true, "end": "success", "failure": "", "collisions": 0,
      "sim_seconds": 30.5, "wall_seconds": 41.0, "path_length_m": 45.3, "optimum_m": 43.1,
      "flown_over_optimum": 1.051, "paths": 55, "min_clearance_m": 0.54, "state": "estimate",
      "depth_to_command_max_s": 0.31, "estimate": {"samples": 7000, "position_rms_m": 0.021, "position_nees_mean": 2.7}})");
  const CampaignRun r = readRun(file, "wall", 2, 0);
  EXPECT_TRUE(r.success);
  EXPECT_EQ(r.state, "estimate");
  ASSERT_TRUE(r.estimate_rms_m.has_value());
  EXPECT_DOUBLE_EQ(*r.estimate_rms_m, 0.021);
  EXPECT_EQ(r.estimate_nees, std::optional<double>(2.7));
  EXPECT_EQ(r.depth_to_command_max_s, std::optional<double>(0.31));
  EXPECT_EQ(r.seed, 2U);
  EXPECT_EQ(r.replans, 55);
  ASSERT_TRUE(r.flown_over_optimum.has_value());
  EXPECT_DOUBLE_EQ(*r.flown_over_optimum, 1.051);
  // a success the launcher's exit status contradicts is not one
  EXPECT_FALSE(readRun(file, "wall", 2, 1).success);
  fs::remove_all(dir);
}

TEST(Campaign, AMissingOrForeignSummaryIsAnErrorNamingTheFile)
{
  const fs::path dir = test::scratchDir("quad_campaign_bad");
  EXPECT_THROW(readRun(dir / "none.json", "w", 1, 1), std::runtime_error);
  const auto other = writeSummary(dir, "b.json", R"({"name": "not a summary"})");
  try {
    readRun(other, "w", 1, 0);
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(other.string()), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Campaign, TheTableAndTheJsonCountTheSameRuns)
{
  CampaignRun ok;
  ok.world = "wall";
  ok.success = true;
  ok.end = "success";
  ok.flown_over_optimum = 1.05;
  CampaignRun sealed;
  sealed.world = "sealed";
  sealed.end = "no_path";
  sealed.exit_status = 3;
  sealed.failure = "no path: known-occupied space seals the goal off";
  const std::vector<CampaignRun> runs{ok, sealed};
  const std::string text = table(runs);
  EXPECT_NE(text.find("1 of 2 runs succeeded"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(toJson(runs));
  EXPECT_EQ(j["succeeded"], 1);
  EXPECT_EQ(j["runs_total"], 2);
  EXPECT_EQ(j["runs"][1]["end"], "no_path");
  EXPECT_TRUE(j["runs"][1]["flown_over_optimum"].is_null());
  EXPECT_DOUBLE_EQ(j["runs"][0]["flown_over_optimum"].get<double>(), 1.05);
}

}  // namespace
}  // namespace quad::campaign
