// SPDX-License-Identifier: BSD-3-Clause
// campaign.html: the success rate over each pair of dimensions, the runs linked to their
// reports, the distributions.
#include "quad/campaign/campaign_report.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "scratch.hpp"

namespace quad::campaign {
namespace {

namespace fs = std::filesystem;

CampaignRun run(const std::string& density, const std::string& speed, std::uint64_t forest, bool success)
{
  CampaignRun r;
  r.world = "benchmark_forest";
  r.params = {{"world:forest.density", density}, {"control:follower.max_speed", speed}};
  r.name = "f-density" + density + "-max_speed" + speed + "-forest" + std::to_string(forest);
  r.success = success;
  r.end = success ? "success" : "failed";
  r.flown_over_optimum = success ? std::optional<double>(1.02) : std::nullopt;
  r.time_to_goal_s = success ? std::optional<double>(9.5) : std::nullopt;
  r.min_clearance_m = 0.2;
  return r;
}

TEST(CampaignReport, TheSuccessRateOfEachPairOfAxesIsMappedAndFailedRunsLinkTheirReports)
{
  const fs::path dir = test::scratchDir("quad_campaign_report");
  const std::vector<Axis> axes{parseAxis("world:forest.density=0.02,0.04", "t"),
                               parseAxis("control:follower.max_speed=5,10", "t")};
  // 0.04 at 10 m/s: one of two fails; every other cell: both succeed
  std::vector<CampaignRun> runs;
  for (const std::string d : {"0.02", "0.04"}) {
    for (const std::string v : {"5", "10"}) {
      for (std::uint64_t f = 1; f <= 2; ++f) {
        runs.push_back(run(d, v, f, !(d == "0.04" && v == "10" && f == 2)));
      }
    }
  }
  const std::string failed = runs.back().name;
  fs::create_directories(dir / failed / "run");
  std::ofstream(dir / failed / "run" / "report.html") << "<html></html>";

  const fs::path page = writeCampaignReport(runs, axes, dir);
  EXPECT_EQ(page, dir / "campaign.html");
  const std::string html = test::readFile(page);
  EXPECT_NE(html.find("7 of 8 runs succeeded"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"" + failed + "/run/report.html\">" + failed + "</a>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<a href=\"" + runs.front().name), std::string::npos) << "a run without a report is not linked";
  // one pair of dimensions (one world, one seed): density x speed
  const std::string map = test::readFile(dir / "campaign_success_0.svg");
  EXPECT_FALSE(fs::exists(dir / "campaign_success_1.svg"));
  EXPECT_NE(map.find("density x max_speed"), std::string::npos) << map;
  // three cells of 2/2 and one of 1/2
  std::size_t full = 0;
  for (auto at = map.find(">2/2<"); at != std::string::npos; at = map.find(">2/2<", at + 1)) {
    ++full;
  }
  EXPECT_EQ(full, 3U) << map;
  EXPECT_NE(map.find(">1/2<"), std::string::npos) << map;
  for (const char* figure : {"campaign_flown_over_optimum.svg", "campaign_closest_approach.svg", "campaign_time_to_goal.svg"}) {
    EXPECT_NE(html.find(std::string("src=\"") + figure + "\""), std::string::npos) << figure;
    EXPECT_EQ(test::readFile(dir / figure).rfind("<svg ", 0), 0U) << figure;
  }
  EXPECT_NE(test::readFile(dir / "campaign_time_to_goal.svg").find("7 runs"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quad::campaign
