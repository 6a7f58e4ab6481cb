// SPDX-License-Identifier: BSD-3-Clause
// A campaign's sweep: axes read from the command line and from a campaign file, their product
// (each cell once), and world variants with their generators' parameters set.
#include "quad/campaign/sweep.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "quad/campaign/campaign.hpp"
#include "quad/campaign/campaign_file.hpp"
#include "quad/common/params.hpp"
#include "scratch.hpp"

namespace quad::campaign {
namespace {

namespace fs = std::filesystem;

/// The problems of a ConfigError `f` throws, joined; "" when it throws none.
template <typename F>
std::string problemsOf(F f)
{
  try {
    f();
  } catch (const common::ConfigError& e) {
    std::string all;
    for (const auto& p : e.problems()) {
      all += p + "\n";
    }
    return all;
  }
  return "";
}

TEST(Sweep, AnAxisTakesAListOrARangeOfWholeNumbers)
{
  const Axis speed = parseAxis("control:follower.max_speed=3,5,7.5", "--set");
  EXPECT_EQ(speed.key, "control:follower.max_speed");
  EXPECT_EQ(speed.values, (std::vector<std::string>{"3", "5", "7.5"}));
  EXPECT_FALSE(speed.isWorld());
  EXPECT_EQ(speed.shortName(), "max_speed");
  const Axis seeds = parseAxis("world:forest.seed=8..11", "--set");
  EXPECT_TRUE(seeds.isWorld());
  EXPECT_EQ(seeds.generatorKey(), (std::pair<std::string, std::string>{"forest", "seed"}));
  EXPECT_EQ(seeds.values, (std::vector<std::string>{"8", "9", "10", "11"}));
}

TEST(Sweep, AMalformedAxisIsRefusedNamingItsText)
{
  for (const std::string bad : {"control=3", "follower.max_speed=3", ":x=3", "control:=3", "control:x=",
                                "control:x=3,,5", "world:forest.seed=5..2", "world:forest.seed=1..x", "world:forest=1",
                                "world:.density=1"}) {
    const std::string problems = problemsOf([&] { parseAxis(bad, "--set"); });
    EXPECT_NE(problems.find("--set"), std::string::npos) << bad << ": " << problems;
  }
}

TEST(Sweep, TheProductFliesEveryCellOnceWorldsOutermostSeedsInnermost)
{
  const std::vector<fs::path> worlds{"/w/a.yaml", "/w/b.yaml"};
  const std::vector<Axis> axes{parseAxis("world:forest.density=0.02,0.04", "t"),
                               parseAxis("control:follower.max_speed=3,5,7", "t")};
  const auto runs = planRuns(worlds, axes, 2);
  ASSERT_EQ(runs.size(), 2U * 2U * 3U * 2U);
  std::set<std::tuple<std::string, std::string, std::string, std::uint64_t>> cells;
  std::set<std::string> names;
  for (const PlannedRun& r : runs) {
    ASSERT_EQ(r.params.size(), 2U);
    cells.emplace(r.world.string(), r.params[0].second, r.params[1].second, r.seed);
    names.insert(r.name);
    EXPECT_EQ(r.moduleSets(), (std::vector<std::string>{"control:follower.max_speed=" + r.params[1].second}));
    EXPECT_EQ(r.worldParams(), (std::vector<std::pair<std::string, std::string>>{r.params[0]}));
  }
  EXPECT_EQ(cells.size(), runs.size());  // no cell twice
  EXPECT_EQ(names.size(), runs.size());  // nor a folder
  EXPECT_EQ(runs.front().name, "a-density0.02-max_speed3-seed1");
  EXPECT_EQ(runs[1].name, "a-density0.02-max_speed3-seed2");
  EXPECT_EQ(runs[2].name, "a-density0.02-max_speed5-seed1");
  EXPECT_EQ(runs.back().name, "b-density0.04-max_speed7-seed2");
  // without axes: the worlds and seeds alone
  EXPECT_EQ(planRuns(worlds, {}, 3).size(), 6U);
}

TEST(Sweep, ManyAxesNameTheirFoldersWithinWhatAFileSystemHoldsAndStillApart)
{
  // Fifteen axes named the cells past 255 bytes, more than a file system holds in one name.
  std::vector<Axis> axes;
  for (int i = 0; i < 15; ++i) {
    axes.push_back(parseAxis(fmt::format("control:gains.a_rather_long_parameter_name_{}=1.25,2.5", i), "t"));
  }
  const auto runs = planRuns({"/w/benchmark_forest.yaml"}, axes, 1);
  ASSERT_EQ(runs.size(), 1U << 15U);
  std::set<std::string> names;
  for (const PlannedRun& r : runs) {
    EXPECT_LE(r.name.size(), 160U) << r.name;
    names.insert(r.name);
  }
  EXPECT_EQ(names.size(), runs.size());
  EXPECT_TRUE(runs.front().name.starts_with("benchmark_forest-a_rather_long_parameter_name_01.25-")) << runs.front().name;
  // a short one is left whole
  EXPECT_EQ(planRuns({"/w/a.yaml"}, {axes.front()}, 1).front().name, "a-a_rather_long_parameter_name_01.25-seed1");
}

TEST(Sweep, AnAxisNamedTwiceOrTwoWorldsOfOneNameAreRefused)
{
  const Axis a = parseAxis("control:follower.max_speed=3", "t");
  EXPECT_NE(problemsOf([&] { planRuns({"/w/a.yaml"}, {a, a}, 1); }).find("named twice"), std::string::npos);
  EXPECT_NE(problemsOf([&] { planRuns({"/w/a.yaml", "/v/a.yaml"}, {}, 1); }).find("a second world named a"),
            std::string::npos);
  // two axes ending in the same word, or in "seed" (the plant's), name their folders by their keys
  const auto runs = planRuns({"/w/a.yaml"}, {parseAxis("control:x.seed=1", "t"), parseAxis("world:forest.seed=2", "t")}, 1);
  EXPECT_EQ(runs.front().name, "a-control_x.seed1-forest.seed2-seed1");
  const auto speeds = planRuns({"/w/a.yaml"}, {parseAxis("control:follower.max_speed=3", "t"),
                                               parseAxis("control:planner.max_speed=4", "t")}, 1);
  EXPECT_EQ(speeds.front().name, "a-control_follower.max_speed3-control_planner.max_speed4-seed1");
}

TEST(Sweep, AWorldVariantSetsTheKeyInEveryGeneratorOfItsTypeAndNothingElse)
{
  const fs::path dir = test::scratchDir("quad_sweep_world");
  const fs::path world = dir / "w.yaml";
  std::ofstream(world) << "bounds: {min: [0, -15, 0], max: [60, 15, 6]}\nstart: [10, 0, 0]\ngoal: [50, 0, 2]\n"
                          "generators:\n"
                          "  - {type: forest, seed: 1, min: [0, -15], max: [30, 15], density: 0.04}\n"
                          "  - {type: forest, seed: 2, min: [30, -15], max: [60, 15], density: 0.04}\n"
                          "  - {type: pillars, seed: 3}\n"
                          "maps:\n  - {file: scans/a.bt}\n  - {file: /abs/b.ply, resolution: 0.1}\n";
  const YAML::Node v = YAML::Load(worldVariant(world, {{"world:forest.density", "0.02"}, {"world:forest.seed", "7"}}));
  for (int i = 0; i < 2; ++i) {
    EXPECT_DOUBLE_EQ(v["generators"][i]["density"].as<double>(), 0.02);
    EXPECT_EQ(v["generators"][i]["seed"].as<int>(), 7);
  }
  EXPECT_EQ(v["generators"][2]["seed"].as<int>(), 3);  // another type keeps its own
  EXPECT_EQ(v["goal"][0].as<double>(), 50.0);
  // the variant lives in the run's folder: its scans are named where the world's are
  EXPECT_EQ(v["maps"][0]["file"].as<std::string>(), (fs::absolute(dir) / "scans" / "a.bt").lexically_normal().string());
  EXPECT_EQ(v["maps"][1]["file"].as<std::string>(), "/abs/b.ply");
  const std::string problems = problemsOf([&] { worldVariant(world, {{"world:wall.x", "1"}}); });
  EXPECT_NE(problems.find(world.string()), std::string::npos) << problems;
  EXPECT_NE(problems.find("no wall generator"), std::string::npos) << problems;
  fs::remove_all(dir);
}

TEST(Sweep, ACampaignFileIsReadWithPathsFromItsFolderAndCheckedWhole)
{
  const fs::path dir = test::scratchDir("quad_sweep_file");
  std::ofstream(dir / "m.yaml") << "name: m\n";
  std::ofstream(dir / "w.yaml") << "bounds: {min: [0, 0, 0], max: [1, 1, 1]}\n";
  std::ofstream(dir / "c.yaml") << "manifest: m.yaml\nworlds: [w.yaml]\nseeds: 2\njobs: 2\nwall_timeout: 300\n"
                                   "layout: composed\nrecord: false\naxes:\n  world:forest.seed: 1..3\n"
                                   "  control:follower.max_speed: [3, 7]\n";
  const CampaignFile c = readCampaignFile(dir / "c.yaml");
  EXPECT_EQ(c.manifest, dir / "m.yaml");
  EXPECT_EQ(c.worlds, (std::vector<fs::path>{dir / "w.yaml"}));
  EXPECT_EQ(c.seeds, 2);
  EXPECT_EQ(c.jobs, 2);
  EXPECT_EQ(c.wall_timeout_s, 300.0);
  EXPECT_EQ(c.layout, "composed");
  EXPECT_FALSE(c.state.has_value());
  EXPECT_EQ(c.record, false);
  ASSERT_EQ(c.axes.size(), 2U);
  EXPECT_EQ(c.axes[0].key, "world:forest.seed");  // in the order written
  EXPECT_EQ(c.axes[0].values, (std::vector<std::string>{"1", "2", "3"}));
  EXPECT_EQ(c.axes[1].values, (std::vector<std::string>{"3", "7"}));

  std::ofstream(dir / "bad.yaml") << "manifest: none.yaml\nworlds: [w.yaml]\nseeds: 1.5\njobs: 0\nlayout: flat\n"
                                     "speed: 3\nrecord: no\naxes:\n  max_speed: [3]\n  control:x: [[1]]\n";
  const std::string problems = problemsOf([&] { readCampaignFile(dir / "bad.yaml"); });
  for (const std::string expected : {"bad.yaml:manifest: none.yaml: no such file", "bad.yaml:seeds: 1.5",
                                     "bad.yaml:jobs: 0", "bad.yaml:layout: flat", "bad.yaml:speed", "bad.yaml:record: no", "axes.max_speed",
                                     "axes.control:x"}) {
    EXPECT_NE(problems.find(expected), std::string::npos) << expected << " not in:\n" << problems;
  }
  fs::remove_all(dir);
}

TEST(Sweep, TheTableHasAColumnAndTheJsonTheValuesOfEveryAxis)
{
  const std::vector<Axis> axes{parseAxis("control:follower.max_speed=3,7", "t")};
  CampaignRun r;
  r.world = "open";
  r.name = "open-max_speed7-seed1";
  r.params = {{"control:follower.max_speed", "7"}};
  r.success = true;
  const std::string text = table({r}, axes);
  EXPECT_NE(text.find("max_speed"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(toJson({r}, axes));
  EXPECT_EQ(j["axes"]["control:follower.max_speed"], (nlohmann::json{"3", "7"}));
  EXPECT_EQ(j["runs"][0]["params"]["control:follower.max_speed"], "7");
  EXPECT_EQ(j["runs"][0]["name"], "open-max_speed7-seed1");
}

}  // namespace
}  // namespace quad::campaign
