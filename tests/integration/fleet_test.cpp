// SPDX-License-Identifier: BSD-3-Clause
// Fleets (DDS domains 77 and 78): several vehicles, each with its own modules, flown by one
// manifest in lockstep with a fixed seed; each reads the run's summary and exit status, and
// two runs' recordings, one with a process per module and one composed, are compared.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "recording_diff.hpp"
#include "quad/common/params.hpp"
#include "quad/planning/planning_params.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

/// [m] The separation the shipped planning config keeps between two vehicles.
double configuredSeparation()
{
  return quad::common::loadParams(fs::path(QUAD_SOURCE_DIR) / "configs/planning.yaml", quad::planning::planningSchema())
      .getDouble("fleet.separation");
}

/// Flies `manifest` on its own domain (recorded to `recording` when given, in `dir`); every
/// vehicle must reach its goal with no collision of any kind, and no two vehicles come closer
/// than the configured separation.
void expectEveryVehicleReachesItsGoalApart(const fs::path& manifest, int domain, std::size_t vehicles,
                                           const fs::path& dir, const std::optional<fs::path>& recording = {},
                                           const std::string& layout = "distributed")
{
  std::vector<std::string> argv{QUAD_TOOL, "launch", manifest.string(), "--domain", std::to_string(domain), "--quiet",
                                "--no-report", "--wall-timeout", "400", "--summary", (dir / "summary.json").string(),
                                "--log-dir", (dir / "run").string(), "--layout", layout};
  if (recording) {
    argv.insert(argv.end(), {"--record", recording->string()});
  } else {
    argv.push_back("--no-record");
  }
  ChildProcess launch(argv);
  const auto status = launch.wait(430s);
  ASSERT_TRUE(status.has_value()) << "quad launch did not end within 430 s\n" << launch.output();
  const auto summary = nlohmann::json::parse(quad::test::readFile(dir / "summary.json"), nullptr, false);
  ASSERT_TRUE(summary.is_object()) << launch.output();
  EXPECT_EQ(*status, 0) << summary.dump(2) << launch.output();
  EXPECT_EQ(summary["success"], true) << summary.dump(2);
  EXPECT_EQ(summary["collisions"], 0) << summary.dump(2);
  ASSERT_TRUE(summary["vehicles"].is_array()) << summary.dump(2);
  ASSERT_EQ(summary["vehicles"].size(), vehicles) << summary.dump(2);
  for (const auto& v : summary["vehicles"]) {
    EXPECT_EQ(v["end"], "success") << v.dump(2);
    EXPECT_EQ(v["collisions"], 0) << v.dump(2);
    EXPECT_LT(v["goal_distance_m"].get<double>(), 2.5) << v.dump(2);  // landed at its own goal
  }
  ASSERT_TRUE(summary["min_separation_m"].is_number()) << summary.dump(2);
  EXPECT_GE(summary["min_separation_m"].get<double>(), configuredSeparation()) << summary.dump(2);
}

TEST(Fleet, ThreeVehiclesWhoseLinesCrossReachEveryGoalApart)
{
  const fs::path dir = quad::test::scratchDir("quad_fleet_crossing");
  expectEveryVehicleReachesItsGoalApart(fs::path(QUAD_SOURCE_DIR) / "bringup/fleet.yaml", 77, 3, dir);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Fleet, TwoVehiclesMeetingHeadOnInACorridorKeepTheSeparationAndTwoRunsRecordTheSameMessagesComposedOrNot)
{
  // GIVEN the head-on meeting flown twice in lockstep, each run recorded: with a process per
  // module, then composed (a container per vehicle for its mapper and planner, one for its
  // estimator and controller, the plant alone)
  const fs::path dir = quad::test::scratchDir("quad_fleet_head_on");
  const fs::path manifest = fs::path(QUAD_SOURCE_DIR) / "tests/fixtures/head_on.yaml";
  expectEveryVehicleReachesItsGoalApart(manifest, 78, 2, dir / "first", dir / "first.mcap");
  expectEveryVehicleReachesItsGoalApart(manifest, 78, 2, dir / "second", dir / "second.mcap", "composed");
  // WHEN the recordings are compared message by message THEN each vehicle's samples are the
  // same in both, whatever turns the two vehicles' writers took within a step or which
  // process hosted them
  quad::test::expectIdenticalRecordings(QUAD_TOOL, dir / "first.mcap", dir / "second.mcap", 15, 50000);
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
