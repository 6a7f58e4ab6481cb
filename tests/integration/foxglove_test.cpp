// SPDX-License-Identifier: BSD-3-Clause
// The independent check: quad recordings read with Foxglove's own MCAP reader and OMG IDL
// decoder (npm packages, installed here with npm ci): every message decoded, the decoded
// values equal to what quad topic echo printed for the same samples, and the demo's display
// topics what Foxglove's 3D panel needs to draw the flight.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "npm_package.hpp"
#include "process.hpp"
#include "quad/dds/topics.hpp"
#include "quad/world/world_file.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

const std::map<std::string, std::string> kEnv{{"QUAD_DOMAIN_ID", "196"}, {"QUAD_TRANSPORT", "udp"}};

fs::path foxgloveTools()
{
  return quad::test::installNpmPackage({QUAD_NPM, QUAD_SOURCE_DIR, QUAD_BUILD_DIR, "foxglove", "@foxglove/ws-protocol"},
                                       {"bridge_client.mjs", "check.mjs", "display_topics.mjs", "slow_client.mjs"});
}

TEST(Foxglove, ItsReaderDecodesEveryRecordedMessageToWhatQuadTopicEchoPrinted)
{
  const fs::path tools = foxgloveTools();
  ASSERT_TRUE(fs::exists(tools / "node_modules/@mcap/core"));
  const fs::path dir = quad::test::scratchDir("quad_foxglove");
  const std::string file = (dir / "plant.mcap").string();
  // Every topic the plant writes, named, so that the recorder has them before the plant starts.
  ChildProcess record({QUAD_TOOL, "record", "-q", "-o", file, "--duration", "7", "quad/sim/state", "quad/sim/imu",
                       "quad/sim/clock", "quad/sim/depth", "quad/sim/events", "quad/system/heartbeat"},
                      kEnv);  // zstd chunks
  ASSERT_TRUE(record.waitForOutput("record: domain 196", 10s)) << record.output();
  // The echo takes what it can of the run (a newest-only reader under load skips samples):
  // it ends after 600 samples or 8 s.
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/state", "--json", "-n", "600", "--timeout", "8",
                     "--max-elements", "100000"},
                    kEnv);
  ChildProcess plant({QUAD_PLANT_NODE, "--config", QUAD_CONFIG_DIR "/plant.yaml", "--set", "sim.duration=4"}, kEnv);
  ASSERT_EQ(plant.wait(30s), 0) << plant.output();
  ASSERT_TRUE(echo.wait(30s)) << echo.output();
  ASSERT_EQ(record.wait(30s), 0) << record.output();
  std::ofstream(dir / "echo.jsonl") << echo.output();
  ChildProcess check({QUAD_NODE, (tools / "check.mjs").string(), file, (dir / "echo.jsonl").string(), "quad/sim/state"});
  const auto status = check.wait(120s);
  ASSERT_TRUE(status) << check.output();
  EXPECT_EQ(*status, 0) << check.output();
  // State is best effort: the recorder and the echo may each miss a sample the other got.
  std::smatch m;
  const std::string out = check.output();
  ASSERT_TRUE(std::regex_search(out, m, std::regex(R"(; (\d+) quad/sim/state samples equal to the echo)"))) << out;
  EXPECT_GE(std::stoi(m[1].str()), 50) << out;  // the samples both the recorder and the echo got
  fs::remove_all(dir);
}

TEST(Foxglove, TheDemosDisplayTopicsHoldTheFlightAsFoxglovesPanelsReadIt)
{
  const fs::path tools = foxgloveTools();
  ASSERT_TRUE(fs::exists(tools / "node_modules/@mcap/core"));
  const fs::path dir = quad::test::scratchDir("quad_foxglove_display");
  const fs::path run = dir / "run";
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--domain", "161", "--quiet",
                       "--wall-timeout", "300", "--no-report", "--log-dir", run.string()});
  const auto flown = launch.wait(330s);
  ASSERT_TRUE(flown && *flown == 0) << launch.output();
  ChildProcess check({QUAD_NODE, (tools / "display_topics.mjs").string(), (run / "recording.mcap").string()});
  const auto status = check.wait(120s);
  ASSERT_TRUE(status) << check.output();
  ASSERT_EQ(*status, 0) << check.output();
  const auto out = check.output();
  const auto summary = nlohmann::json::parse(out.substr(out.find('{')), nullptr, false);
  ASSERT_TRUE(summary.is_object()) << out;

  // Every display topic recorded in Foxglove's schema, and every message decoded.
  for (const char* topic : {"quad/display/transforms", "quad/display/trajectory", "quad/display/true_trajectory",
                            "quad/display/path", "quad/display/plan", "quad/display/map", "quad/display/scene",
                            "quad/display/depth", "quad/display/log"}) {
    const auto& c = summary["channels"][topic];
    ASSERT_TRUE(c.is_object()) << topic << "\n" << out;
    EXPECT_TRUE(c["schema"].get<std::string>().starts_with("foxglove::")) << topic;
    EXPECT_EQ(c["schema_encoding"], "omgidl") << topic;
    EXPECT_EQ(c["message_encoding"], "cdr") << topic;
    EXPECT_GT(c["messages"].get<int>(), 0) << topic;
    EXPECT_EQ(c["decoded"], c["messages"]) << topic;
  }
  // The frames a 3D panel resolves: the body (the estimate flown on) and the truth in the
  // world, the depth camera on the body; unit rotations; the estimate near the truth.
  const auto frames = summary["transforms"]["frames"].get<std::vector<std::string>>();
  for (const char* f : {"world>body", "world>body_true", "body>depth_front"}) {
    EXPECT_NE(std::find(frames.begin(), frames.end(), f), frames.end()) << f << "\n" << out;
  }
  EXPECT_LT(summary["transforms"]["max_quaternion_norm_error"].get<double>(), 1e-9);
  EXPECT_LT(summary["transforms"]["max_body_truth_gap_m"].get<double>(), 0.5);
  // The trajectories cover the ~55 m flight, a pose at least every 25 cm, in the world frame.
  EXPECT_EQ(summary["trajectory"]["frame"], "world");
  EXPECT_GT(summary["trajectory"]["poses"].get<int>(), 220);
  EXPECT_GT(summary["true_trajectory"]["poses"].get<int>(), 220);
  // The map: coloured points in the world frame, within its bounds and the mapper's margin.
  const quad::world::World world = quad::world::loadWorld(QUAD_CONFIG_DIR "/worlds/demo.yaml");
  const auto& map = summary["map"];
  EXPECT_EQ(map["frame"], "world");
  EXPECT_EQ(map["stride"], 16);
  EXPECT_GT(map["points"].get<int>(), 1000);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto axis = static_cast<Eigen::Index>(i);
    EXPECT_GE(map["min"][i].get<double>(), world.bounds().min[axis] - 1.0) << i;
    EXPECT_LE(map["max"][i].get<double>(), world.bounds().max[axis] + 1.0) << i;
  }
  // Depth: hits only, within the camera's range, in its own frame.
  EXPECT_EQ(summary["depth"]["frames"], nlohmann::json::array({"depth_front"}));
  EXPECT_LE(summary["depth"]["max_range_m"].get<double>(), 20.0 + 1e-3);
  // The scene: every obstacle of the world, and the goal where the world puts it.
  const auto& scene = summary["scene"];
  EXPECT_EQ(scene["cubes"].get<std::size_t>() + scene["cylinders"].get<std::size_t>() +
                scene["spheres"].get<std::size_t>() - 1,  // the goal's sphere
            world.obstacles().size());
  EXPECT_NEAR(scene["goal"]["x"].get<double>(), world.goal().x(), 1e-9);
  EXPECT_NEAR(scene["goal"]["y"].get<double>(), world.goal().y(), 1e-9);
  EXPECT_NEAR(scene["goal"]["z"].get<double>(), world.goal().z(), 1e-9);
  // The log: the modes and the plan, from control and planning, at Foxglove's levels.
  EXPECT_GE(summary["log"]["lines"].get<int>(), 5);
  const auto names = summary["log"]["names"].get<std::vector<std::string>>();
  for (const char* n : {"control", "planning"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  }
  for (const auto& [level, n] : summary["log"]["levels"].items()) {
    EXPECT_GE(std::stoi(level), 1) << level;  // DEBUG..FATAL, never UNKNOWN
    EXPECT_LE(std::stoi(level), 5) << level;
  }
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Foxglove, ItsWebSocketClientSeesTheStackThroughQuadBridgeAndItsGoalIsTaken)
{
  const fs::path tools = foxgloveTools();
  ASSERT_TRUE(fs::exists(tools / "node_modules/@foxglove/ws-protocol"));
  const fs::path dir = quad::test::scratchDir("quad_foxglove_bridge");
  ChildProcess bridge({QUAD_TOOL, "bridge", "--domain", "162", "--port", "0", "-q"});
  ASSERT_TRUE(bridge.waitForOutput("listening on ws://", 20s)) << bridge.output();
  std::smatch port;
  const std::string listening = bridge.output();
  ASSERT_TRUE(std::regex_search(listening, port, std::regex(R"(ws://127\.0\.0\.1:(\d+))"))) << listening;
  // The client connects first, then the demo flies; once the state and the map flow, the
  // client sends goal 7 halfway along the forest and waits for the planner's answer.
  ChildProcess client({QUAD_NODE, (tools / "bridge_client.mjs").string(), "ws://127.0.0.1:" + port[1].str(), "7", "30",
                       "0", "2", "120"});
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--domain", "162",
                       "--quiet", "--wall-timeout", "200", "--no-record", "--log-dir", (dir / "run").string()});
  const auto answered = client.wait(150s);
  launch.signal(SIGINT);
  EXPECT_TRUE(launch.wait(60s)) << launch.output();
  bridge.signal(SIGINT);
  const auto bridge_status = bridge.wait(30s);
  ASSERT_TRUE(answered) << client.output();
  const auto out = client.output();
  const auto summary = nlohmann::json::parse(out.substr(out.find('{')), nullptr, false);
  ASSERT_TRUE(summary.is_object()) << out;
  EXPECT_EQ(*answered, 0) << out;
  EXPECT_TRUE(summary["errors"].empty()) << out;
  EXPECT_EQ(summary["capabilities"], nlohmann::json::array({"clientPublish"}));
  // Every contract is a channel, the display topics among them.
  EXPECT_EQ(summary["channels"].get<std::size_t>(), quad::dds::topics::kAll.size()) << out;
  EXPECT_GE(summary["decoded"]["quad/sim/state"].get<int>(), 20) << out;
  EXPECT_GE(summary["decoded"]["quad/display/map"].get<int>(), 1) << out;
  // The goal published through the bridge reached the planner, which took it.
  ASSERT_TRUE(summary["goal_answer"].is_object()) << out;
  EXPECT_TRUE(summary["goal_answer"]["accepted"].get<bool>()) << out;
  // A topic the stack does not take from outside is refused, naming it.
  bool refused = false;
  for (const auto& s : summary["statuses"]) {
    refused |= s["level"] == 2 && s["message"].get<std::string>().find("quad/control/actuators") != std::string::npos;
  }
  EXPECT_TRUE(refused) << out;
  ASSERT_TRUE(bridge_status) << bridge.output();
  EXPECT_EQ(*bridge_status, 0) << bridge.output();
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

TEST(Foxglove, AClientThatStopsReadingDoesNotHoldTheMissionBack)
{
  const fs::path tools = foxgloveTools();
  const fs::path dir = quad::test::scratchDir("quad_foxglove_slow");
  // A 1 MiB queue per client: the slow client's fills within seconds of the flight.
  ChildProcess bridge({QUAD_TOOL, "bridge", "--domain", "163", "--port", "0", "-q", "--client-queue", "1048576"});
  ASSERT_TRUE(bridge.waitForOutput("listening on ws://", 20s)) << bridge.output();
  std::smatch port;
  const std::string listening = bridge.output();
  ASSERT_TRUE(std::regex_search(listening, port, std::regex(R"(ws://127\.0\.0\.1:(\d+))"))) << listening;
  ChildProcess slow({QUAD_NODE, (tools / "slow_client.mjs").string(), "ws://127.0.0.1:" + port[1].str()});
  ASSERT_TRUE(slow.waitForOutput("stalled", 20s)) << slow.output();
  // The mission flies to the end while every topic is sent to a client that reads nothing.
  ChildProcess launch({QUAD_TOOL, "launch", std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml", "--domain", "163",
                       "--quiet", "--wall-timeout", "200", "--no-record", "--summary", (dir / "summary.json").string(),
                       "--log-dir", (dir / "run").string()});
  const auto flown = launch.wait(230s);
  bridge.signal(SIGINT);
  const auto bridge_status = bridge.wait(30s);
  slow.signal(SIGKILL);
  slow.wait(10s);
  ASSERT_TRUE(flown) << launch.output();
  EXPECT_EQ(*flown, 0) << launch.output();
  const auto summary = nlohmann::json::parse(quad::test::readFile(dir / "summary.json"), nullptr, false);
  ASSERT_TRUE(summary.is_object());
  EXPECT_TRUE(summary["success"].get<bool>()) << summary.dump(1);
  // The bridge dropped what the slow client could not take, and ended cleanly.
  ASSERT_TRUE(bridge_status) << bridge.output();
  EXPECT_EQ(*bridge_status, 0) << bridge.output();
  std::smatch dropped;
  const std::string out = bridge.output();
  ASSERT_TRUE(std::regex_search(out, dropped, std::regex(R"(client 127\.0\.0\.1:\d+( left)?: (\d+) messages dropped)"))) << out;
  EXPECT_GT(std::stoull(dropped[2].str()), 0U) << out;
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
