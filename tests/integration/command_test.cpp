// SPDX-License-Identifier: BSD-3-Clause
// quad command: the operator's commands to the flying demo, each answered, with its exit status.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "json_lines.hpp"
#include "process.hpp"
#include "scratch.hpp"
#include "wait.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

constexpr int kDomain = 66;

/// `quad command ARGS...` on `domain`: its exit status and what it printed.
std::pair<int, std::string> command(std::vector<std::string> args, int domain = kDomain)
{
  std::vector<std::string> argv = {QUAD_TOOL, "command", "--domain", std::to_string(domain), "--timeout", "20"};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess c(argv);
  const auto rc = c.wait(60s);
  return {rc.value_or(-1), c.output()};
}

TEST(Command, WithNobodyToAnswerACommandEndsInTimeWithItsOwnStatus)
{
  std::vector<std::string> argv = {QUAD_TOOL, "command", "--domain", "67", "--timeout", "2", "land"};
  ChildProcess c(argv);
  EXPECT_EQ(c.wait(20s), 3) << c.output();
}

TEST(Command, BadInputIsRefusedBeforeAnythingIsSent)
{
  EXPECT_EQ(command({"goal", "1", "2"}, 67).first, 2);              // a position is three numbers
  EXPECT_EQ(command({"takeoff", "--altitude", "-1"}, 67).first, 2);  // a height above the ground
  EXPECT_EQ(command({"goal", "1", "2", "3", "--tolerance", "0"}, 67).first, 2);
  EXPECT_EQ(command({"fly"}, 67).first, 2);
}

TEST(Command, TheOperatorHoldsResumesRedirectsAndLandsTheDemoAndIsRefusedWhatDoesNotApply)
{
  const fs::path dir = quad::test::scratchDir("quad_command");
  // GIVEN the demo flying its mission in lockstep (the launcher its operator's station too)
  ChildProcess launch({QUAD_TOOL, "launch", "demo", "--domain", std::to_string(kDomain), "--quiet", "--wall-timeout",
                       "240", "--summary", (dir / "summary.json").string(), "--log-dir", (dir / "run").string()});
  ChildProcess status({QUAD_TOOL, "topic", "echo", "quad/control/status", "--json", "--domain",
                       std::to_string(kDomain)});
  ASSERT_TRUE(status.waitForOutput("CONTROL_MISSION", 120s)) << status.output() << launch.output();

  // WHEN the operator asks for a take-off in the air THEN it is refused (exit 1), saying why
  int rc = 0;
  std::string out;
  std::tie(rc, out) = command({"takeoff"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("already in the air"), std::string::npos) << out;
  // WHEN it commands a hold THEN it is taken and the vehicle hovers
  std::tie(rc, out) = command({"hold"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("(now HOVER)"), std::string::npos) << out;
  // WHEN it gives a goal outside the world THEN the planner refuses it, naming it
  std::tie(rc, out) = command({"goal", "1000", "0", "2"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("goal 2 at (1000, 0, 2) is outside the planning bounds"), std::string::npos) << out;
  // WHEN it sends the vehicle back over what it flew THEN the goal is taken with a path, and the
  // mission resumes to it
  std::tie(rc, out) = command({"goto", "2", "0", "2"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("path of"), std::string::npos) << out;
  EXPECT_NE(out.find("(now MISSION)"), std::string::npos) << out;
  // WHEN it commands the landing THEN it is taken, and the run ends short of the world's goal,
  // saying the operator landed it
  std::tie(rc, out) = command({"land"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("(now LAND)"), std::string::npos) << out;
  const auto end = launch.wait(150s);
  ASSERT_TRUE(end.has_value()) << launch.output();
  EXPECT_NE(*end, 0) << launch.output();
  const auto summary = nlohmann::json::parse(quad::test::readFile(dir / "summary.json"), nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << launch.output();
  EXPECT_EQ(summary["success"], false) << summary;
  EXPECT_EQ(summary["collisions"], 0) << summary;
  EXPECT_TRUE(summary["failure"].get<std::string>().starts_with("the operator commanded a landing")) << summary;
  // AND the modes went MISSION, HOVER (the hold), MISSION (the goto), LAND, IDLE
  std::vector<std::string> modes;
  for (const auto& change : summary["modes"]) {
    const std::string text = change.get<std::string>();
    modes.push_back(text.substr(text.find(' ') + 1));
  }
  const std::vector<std::string> expected = {"MISSION", "HOVER", "MISSION", "LAND", "IDLE"};
  auto at = std::find(modes.begin(), modes.end(), "MISSION");
  for (const auto& mode : expected) {
    at = std::find(at, modes.end(), mode);
    ASSERT_NE(at, modes.end()) << mode << " missing or out of order in " << summary;
  }
}

}  // namespace
