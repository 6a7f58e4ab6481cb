// SPDX-License-Identifier: BSD-3-Clause
// What a Slurm submission is made of: the job array's indices and the campaign file its tasks
// read, which must give them the campaign the submitter checked.
#include "quad/campaign/slurm.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "quad/campaign/campaign_file.hpp"
#include "scratch.hpp"

namespace quad::campaign {
namespace {

namespace fs = std::filesystem;

TEST(Slurm, TheRunsToFlyAreTheJobArraysIndicesInRanges)
{
  EXPECT_EQ(arrayRanges({}), "");
  EXPECT_EQ(arrayRanges({4}), "4");
  EXPECT_EQ(arrayRanges({0, 1, 2, 3}), "0-3");
  EXPECT_EQ(arrayRanges({0, 1, 2, 3, 5, 7, 8, 9}), "0-3,5,7-9");
  EXPECT_EQ(arrayRanges({1, 3, 5}), "1,3,5");
}

TEST(Slurm, TheCampaignFileTheTasksReadGivesThemTheSameCampaign)
{
  const fs::path dir = test::scratchDir("quad_slurm_file");
  std::ofstream(dir / "m.yaml") << "name: m\n";
  std::ofstream(dir / "it's a world.yaml") << "bounds: {min: [0, 0, 0], max: [1, 1, 1]}\n";
  CampaignOptions c;
  c.manifest = dir / "m.yaml";
  c.worlds = {dir / "it's a world.yaml"};
  c.seeds = 3;
  c.wall_timeout_s = 321.5;
  c.layout = "composed";
  c.record = false;
  c.axes = {parseAxis("world:forest.density=0.020408,0.04", "t"), parseAxis("control:follower.max_speed=3,7", "t")};
  std::ofstream(dir / "c.yaml") << campaignFileText(c);
  const CampaignFile back = readCampaignFile(dir / "c.yaml");
  EXPECT_EQ(back.manifest, c.manifest);
  EXPECT_EQ(back.worlds, c.worlds);
  EXPECT_EQ(back.seeds, 3);
  EXPECT_EQ(back.wall_timeout_s, 321.5);
  EXPECT_EQ(back.layout, "composed");
  EXPECT_FALSE(back.state.has_value());
  EXPECT_EQ(back.record, false);
  ASSERT_EQ(back.axes.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.axes[i].key, c.axes[i].key);
    EXPECT_EQ(back.axes[i].values, c.axes[i].values);
  }
  // and so the same product, run for run
  const auto a = planRuns(c.worlds, c.axes, c.seeds);
  const auto b = planRuns(back.worlds, back.axes, *back.seeds);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].name, b[i].name);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quad::campaign
