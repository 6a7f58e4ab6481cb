// SPDX-License-Identifier: BSD-3-Clause
// The report as a browser shows it: the demo is flown (DDS domain 129), its run folder's
// report.html is opened in Debian's Chromium, headless, through playwright-core (npm, installed
// here with npm ci), and every figure must be drawn: loaded, at the size its SVG declares, not
// blank, with no console or script error and no failed request. The same for a campaign's
// campaign.html (domains 126 and 127).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "npm_package.hpp"
#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

fs::path browserTools()
{
  return quad::test::installNpmPackage({QUAD_NPM, QUAD_SOURCE_DIR, QUAD_BUILD_DIR, "browser", "playwright-core"},
                                       {"check.mjs"});
}

/// Width and height of a PNG file, from its IHDR chunk.
std::pair<int, int> pngSize(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  unsigned char b[24] = {};
  in.read(reinterpret_cast<char*>(b), sizeof b);
  const auto be = [&](int at) { return (b[at] << 24) | (b[at + 1] << 16) | (b[at + 2] << 8) | b[at + 3]; };
  return {be(16), be(20)};
}

/// check.mjs's answer for `page` of `dir`: its JSON, or a failure.
nlohmann::json checkPage(const fs::path& tools, const fs::path& dir, const std::string& page, const fs::path& png)
{
  ChildProcess check({QUAD_NODE, (tools / "check.mjs").string(), dir.string(), png.string(), page},
                     {{"QUAD_CHROMIUM", QUAD_CHROMIUM}});
  const auto status = check.wait(120s);
  EXPECT_TRUE(status) << check.output();
  EXPECT_EQ(status.value_or(-1), 0) << check.output();
  const std::string out = check.output();
  const auto at = out.rfind("{\"figures\"");
  return nlohmann::json::parse(at == std::string::npos ? std::string() : out.substr(at), nullptr, false);
}

TEST(Report, TheDemosReportIsDrawnByAHeadlessBrowser)
{
  const fs::path tools = browserTools();
  ASSERT_TRUE(fs::exists(tools / "node_modules/playwright-core"));
  const fs::path dir = quad::test::scratchDir("quad_report_browser");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--domain", "129", "--quiet",
                       "--wall-timeout", "300", "--log-dir", run.string()});
  const auto flown = launch.wait(330s);
  ASSERT_TRUE(flown) << launch.output();
  ASSERT_EQ(*flown, 0) << launch.output();
  ASSERT_TRUE(fs::exists(run / "report.html")) << launch.output();

  const auto json = checkPage(tools, run, "report.html", dir / "report.png");
  ASSERT_TRUE(json.is_object());
  EXPECT_TRUE(json["problems"].empty()) << json.dump(2);
  std::set<std::string> drawn;
  for (const auto& f : json["figures"]) {
    EXPECT_TRUE(f["loaded"].get<bool>()) << f;
    EXPECT_GE(f["width"].get<int>(), 800) << f;
    EXPECT_GE(f["height"].get<int>(), 200) << f;
    EXPECT_GT(f["ink"].get<double>(), 0.003) << f;
    drawn.insert(f["src"].get<std::string>());
  }
  EXPECT_EQ(drawn, (std::set<std::string>{"top_view.svg", "side_view.svg", "motion.svg", "tracking.svg", "timeline.svg",
                                          "replanning.svg", "rates.svg", "estimate_error.svg"}));
  // The screenshot holds the whole page: the summary and eight figures, one under the other.
  const auto [width, height] = pngSize(dir / "report.png");
  EXPECT_EQ(width, 1000);
  EXPECT_GT(height, 3000);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Report, ACampaignsPageIsDrawnByAHeadlessBrowserAndLinksItsFailedRunsReport)
{
  const fs::path tools = browserTools();
  ASSERT_TRUE(fs::exists(tools / "node_modules/playwright-core"));
  const fs::path dir = quad::test::scratchDir("quad_campaign_browser");
  const std::string worlds = std::string(QUAD_SOURCE_DIR) + "/configs/worlds/";
  ChildProcess campaign({QUAD_TOOL, "campaign", worlds + "wall.yaml", worlds + "sealed.yaml", "-j", "2", "--domain", "126",
                         "--log-dir", dir.string()});
  const auto flown = campaign.wait(600s);
  ASSERT_TRUE(flown) << campaign.output();
  ASSERT_EQ(*flown, 1) << campaign.output();  // the sealed goal fails
  const std::string html = quad::test::readFile(dir / "campaign.html");
  // the failed run, linked to its own report, which is there
  EXPECT_NE(html.find("<a href=\"sealed-seed1/run/report.html\">sealed-seed1</a>"), std::string::npos) << html;
  EXPECT_TRUE(fs::exists(dir / "sealed-seed1/run/report.html"));
  const auto json = checkPage(tools, dir, "campaign.html", dir / "campaign.png");
  ASSERT_TRUE(json.is_object());
  EXPECT_TRUE(json["problems"].empty()) << json.dump(2);
  std::set<std::string> drawn;
  for (const auto& f : json["figures"]) {
    EXPECT_TRUE(f["loaded"].get<bool>()) << f;
    EXPECT_GE(f["width"].get<int>(), 300) << f;
    EXPECT_GT(f["ink"].get<double>(), 0.003) << f;
    drawn.insert(f["src"].get<std::string>());
  }
  EXPECT_EQ(drawn, (std::set<std::string>{"campaign_success_0.svg", "campaign_flown_over_optimum.svg",
                                          "campaign_closest_approach.svg", "campaign_time_to_goal.svg"}));
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
