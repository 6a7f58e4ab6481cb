// SPDX-License-Identifier: BSD-3-Clause
// A node on the shared skeleton, driven and inspected with the quad command.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <string>

#include "json_lines.hpp"
#include "module_wait.hpp"
#include "process.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;

std::map<std::string, std::string> env(int domain)
{
  return {{"QUAD_DOMAIN_ID", std::to_string(domain)}};
}

TEST(NodeAndTools, EchoPrintsTheHeartbeatAnotherProcessPublished)
{
  ChildProcess node({QUAD_TEST_NODE}, env(130));
  ASSERT_TRUE(quad::test::waitForRunningModule(130, "test_node", 20s)) << node.output();
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/system/heartbeat", "-n", "1", "--timeout",
                     "15"},
                    env(130));
  ASSERT_EQ(echo.wait(20s), 0) << echo.output();
  EXPECT_NE(echo.output().find("module_name: test_node"), std::string::npos) << echo.output();
  EXPECT_NE(echo.output().find("state: MODULE_RUNNING"), std::string::npos) << echo.output();
}

TEST(NodeAndTools, PublishedCommandReachesTheNode)
{
  ChildProcess node({QUAD_TEST_NODE}, env(131));
  ASSERT_TRUE(quad::test::waitForRunningModule(131, "test_node", 20s)) << node.output();
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command",
                    "{kind: COMMAND_HOLD, command_id: 1}"},
                   env(131));
  ASSERT_EQ(pub.wait(20s), 0) << pub.output();
  EXPECT_TRUE(node.waitForOutput("command 4 received (1 so far)", 5s)) << node.output();
}

TEST(NodeAndTools, VehicleOptionPublishesForAVehicleAndEchoesOnlyItsSamples)
{
  ChildProcess five({QUAD_TOOL, "topic", "echo", "quad/planning/goal", "--vehicle", "5", "-n", "1", "--json",
                     "--timeout", "15"},
                    env(72));
  ChildProcess six({QUAD_TOOL, "topic", "echo", "quad/planning/goal", "--vehicle", "6", "-n", "1", "--timeout", "6"},
                   env(72));
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/planning/goal", "{goal_id: 3, p_W: {x: 1, y: 2, z: 3}}",
                    "--vehicle", "5"},
                   env(72));
  ASSERT_EQ(pub.wait(20s), 0) << pub.output();
  ASSERT_EQ(five.wait(20s), 0) << five.output();
  const auto goals = quad::test::jsonLines(five.output());
  ASSERT_EQ(goals.size(), 1U) << five.output();
  EXPECT_EQ(goals[0]["header"]["vehicle_id"], 5) << goals[0];
  EXPECT_EQ(goals[0]["goal_id"], 3) << goals[0];
  EXPECT_EQ(six.wait(20s), 1) << six.output();  // vehicle 6 got no goal
}

void stopsCleanlyOn(int signal_number, int domain)
{
  ChildProcess node({QUAD_TEST_NODE}, env(domain));
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "test_node", 20s)) << node.output();
  node.signal(signal_number);
  EXPECT_EQ(node.wait(5s), 0) << node.output();
}

TEST(NodeAndTools, NodeStopsCleanlyOnSigterm) { stopsCleanlyOn(SIGTERM, 132); }

TEST(NodeAndTools, NodeStopsCleanlyOnSigint) { stopsCleanlyOn(SIGINT, 133); }

TEST(NodeAndTools, TopicListShowsWritersAndReadersOfTheNode)
{
  ChildProcess node({QUAD_TEST_NODE}, env(134));
  ASSERT_TRUE(quad::test::waitForRunningModule(134, "test_node", 20s)) << node.output();
  ChildProcess list({QUAD_TOOL, "topic", "list", "--wait", "3", "--json"}, env(134));
  ASSERT_EQ(list.wait(20s), 0) << list.output();
  const auto out = nlohmann::json::parse(list.output(), nullptr, false);
  ASSERT_TRUE(out.is_object()) << list.output();
  EXPECT_EQ(out["domain"], 134);
  const auto row = [&](const std::string& topic) {
    for (const auto& r : out["topics"]) {
      if (r["topic"] == topic) {
        return r;
      }
    }
    return nlohmann::json();
  };
  const auto heartbeat = row("quad/system/heartbeat");
  EXPECT_EQ(heartbeat["type"], "quad::msg::Heartbeat") << out;
  EXPECT_EQ(heartbeat["writers"], 1) << out;
  EXPECT_EQ(heartbeat["readers"], 0) << out;
  EXPECT_EQ(heartbeat["owner"], "every module") << out;
  EXPECT_EQ(heartbeat["type_matches"], true) << out;
  const auto command = row("quad/system/command");
  EXPECT_EQ(command["writers"], 0) << out;
  EXPECT_EQ(command["readers"], 1) << out;
  EXPECT_EQ(command["owner"], "operator") << out;
}

TEST(NodeAndTools, UnknownTopicIsRefusedWithTheKnownOnes)
{
  ChildProcess echo({QUAD_TOOL, "topic", "echo", "quad/sim/stat"}, env(135));
  EXPECT_EQ(echo.wait(10s), 1) << echo.output();
  EXPECT_NE(echo.output().find("quad: unknown topic 'quad/sim/stat'; quad's topics are:"),
            std::string::npos)
      << echo.output();
  EXPECT_NE(echo.output().find("\n  quad/sim/state\n"), std::string::npos) << echo.output();
}

TEST(NodeAndTools, PublishRefusesABadFieldBeforeSendingAnything)
{
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/planning/goal", "{p_W: {x: 1, q: 2}}"},
                   env(136));
  EXPECT_EQ(pub.wait(10s), 1) << pub.output();
  EXPECT_NE(pub.output().find("quad: quad/planning/goal: p_W.q: unknown field of "
                              "quad::msg::Vector3 (fields: x, y, z)"),
            std::string::npos)
      << pub.output();
}

}  // namespace

namespace {

TEST(NodeAndTools, NodeStartsWithAValidConfig)
{
  ChildProcess node({QUAD_TEST_NODE, "--config", QUAD_FIXTURES "/test_node_ok.yaml"}, env(137));
  EXPECT_TRUE(node.waitForOutput("greeting: from the fixture", 10s)) << node.output();
  EXPECT_TRUE(quad::test::waitForRunningModule(137, "test_node", 20s)) << node.output();
}

TEST(NodeAndTools, NodeRefusesToStartOnABadConfigNamingFileKeyAndValue)
{
  const std::string file = QUAD_FIXTURES "/test_node_bad.yaml";
  ChildProcess node({QUAD_TEST_NODE, "--config", file}, env(138));
  EXPECT_EQ(node.wait(10s), 1) << node.output();
  const std::string& out = node.output();
  EXPECT_NE(out.find(file + ":greting: hi: unknown key (did you mean 'greeting'?)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find(file + ":command_timeout: .nan: not a finite number"), std::string::npos)
      << out;
  EXPECT_NE(out.find("refusing to start"), std::string::npos) << out;
  EXPECT_EQ(out.find("running on domain"), std::string::npos) << out;
}

TEST(NodeAndTools, CheckValidatesTheParametersAndExitsWithoutJoiningTheDomain)
{
  const std::string file = QUAD_FIXTURES "/test_node_ok.yaml";
  ChildProcess good({QUAD_TEST_NODE, "--config", file, "--set", "greeting=hi", "--check"}, env(141));
  EXPECT_EQ(good.wait(10s), 0) << good.output();
  EXPECT_NE(good.output().find("test_node: parameters ok"), std::string::npos) << good.output();
  EXPECT_EQ(good.output().find("running on domain"), std::string::npos) << good.output();
  ChildProcess bad({QUAD_TEST_NODE, "--config", file, "--set", "greting=hi", "--check"}, env(141));
  EXPECT_EQ(bad.wait(10s), 1) << bad.output();
  EXPECT_NE(bad.output().find("greting: hi: unknown key (did you mean 'greeting'?)"), std::string::npos) << bad.output();
}

TEST(NodeAndTools, LaunchCheckRunsEveryModulesOwnCheckWithTheCommandLinesSets)
{
  const std::string demo = std::string(QUAD_SOURCE_DIR) + "/bringup/demo.yaml";
  ChildProcess ok({QUAD_TOOL, "launch", demo, "--set", "control:follower.max_speed=3", "--check"});
  EXPECT_EQ(ok.wait(30s), 0) << ok.output();
  for (const char* layout : {"distributed", "composed"}) {
    ChildProcess bad({QUAD_TOOL, "launch", demo, "--layout", layout, "--set", "control:follower.max_speed=-3", "--check"});
    EXPECT_EQ(bad.wait(30s), 2) << bad.output();
    EXPECT_NE(bad.output().find("follower.max_speed: -3: out of range"), std::string::npos) << layout << bad.output();
  }
  ChildProcess unknown({QUAD_TOOL, "launch", demo, "--set", "controller:follower.max_speed=3", "--check"});
  EXPECT_EQ(unknown.wait(30s), 2) << unknown.output();
  EXPECT_NE(unknown.output().find("no module 'controller' in the manifest"), std::string::npos) << unknown.output();
}

TEST(NodeAndTools, NodeAnswersHelpAndVersionAndRefusesAnUnknownArgumentWithExitCodeTwo)
{
  // --help lists every parameter the config takes, the logging keys included
  ChildProcess help({QUAD_TEST_NODE, "--help"});
  EXPECT_EQ(help.wait(10s), 0) << help.output();
  EXPECT_NE(help.output().find("greeting: string"), std::string::npos) << help.output();
  EXPECT_NE(help.output().find("log.level: string = info"), std::string::npos) << help.output();
  ChildProcess version({QUAD_TEST_NODE, "--version"});
  EXPECT_EQ(version.wait(10s), 0) << version.output();
  EXPECT_NE(version.output().find("quad_test_node 0."), std::string::npos) << version.output();
  ChildProcess bad({QUAD_TEST_NODE, "--bogus"});
  EXPECT_EQ(bad.wait(10s), 2) << bad.output();
  EXPECT_NE(bad.output().find("'--bogus'"), std::string::npos) << bad.output();
}

TEST(NodeAndTools, QuadRefusesAnUnknownSubcommandEvenWithHelpNamingIt)
{
  for (const std::vector<std::string>& words : {std::vector<std::string>{"teleport", "--help"},
                                                std::vector<std::string>{"teleport"},
                                                std::vector<std::string>{"topic", "lst"}}) {
    std::vector<std::string> argv{QUAD_TOOL};
    argv.insert(argv.end(), words.begin(), words.end());
    ChildProcess quad(argv);
    EXPECT_EQ(quad.wait(10s), 2) << quad.output();
    EXPECT_NE(quad.output().find("unknown subcommand '" + std::string(words.front() == "topic" ? "topic lst" : "teleport")),
              std::string::npos)
        << quad.output();
  }
  ChildProcess help({QUAD_TOOL, "topic", "list", "--help"});
  EXPECT_EQ(help.wait(10s), 0) << help.output();
  ChildProcess version({QUAD_TOOL, "--version"});
  EXPECT_EQ(version.wait(10s), 0) << version.output();
  EXPECT_NE(version.output().find("quad 0."), std::string::npos) << version.output();
}

TEST(NodeAndTools, NodeRefusesAMissingConfigFile)
{
  ChildProcess node({QUAD_TEST_NODE, "--config", "/nonexistent/test_node.yaml"}, env(139));
  EXPECT_EQ(node.wait(10s), 1) << node.output();
  EXPECT_NE(node.output().find("/nonexistent/test_node.yaml: cannot open"), std::string::npos)
      << node.output();
}

}  // namespace

namespace {

TEST(NodeAndTools, So3AnswersAndRefusesWithExitCodeTwo)
{
  ChildProcess ok({QUAD_TOOL, "so3", "distance", "--matrix", "1", "0", "0", "0", "0", "-1", "0",
                   "1", "0", "--quat", "0.7071067811865476", "0", "0", "-0.7071067811865476"});
  EXPECT_EQ(ok.wait(10s), 0) << ok.output();
  EXPECT_NE(ok.output().find("(120 deg)"), std::string::npos) << ok.output();
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"convert", "--matrix", "1", "2"},
        std::vector<std::string>{"convert", "--quat", "1", "one", "0", "0"},
        std::vector<std::string>{"convert", "--matrix", "2", "0", "0", "0", "2", "0", "0", "0", "2"},
        std::vector<std::string>{"sample", "-n", "many"}}) {
    std::vector<std::string> argv{QUAD_TOOL, "so3"};
    argv.insert(argv.end(), bad.begin(), bad.end());
    ChildProcess refused(argv);
    EXPECT_EQ(refused.wait(10s), 2) << refused.output();
  }
}

}  // namespace

namespace {

TEST(NodeAndTools, TopicHzMeasuresTheHeartbeatAgainstItsContract)
{
  ChildProcess node({QUAD_TEST_NODE}, {{"QUAD_DOMAIN_ID", "194"}, {"QUAD_TRANSPORT", "udp"}});
  ASSERT_TRUE(quad::test::waitForRunningModule(194, "test_node", 20s)) << node.output();
  ChildProcess hz({QUAD_TOOL, "topic", "hz", "quad/system/heartbeat", "--duration", "4.2", "--window", "2", "--json"},
                  {{"QUAD_DOMAIN_ID", "194"}, {"QUAD_TRANSPORT", "udp"}});
  ASSERT_EQ(hz.wait(20s), 0) << hz.output();
  // The heartbeat's contract is 2 Hz: a 2 s window holds 4 samples, give or take one.
  // A line per 2 s window (the second may be cut by the end at 4.2 s on a busy machine), then
  // the total.
  const auto lines = quad::test::jsonLines(hz.output());
  ASSERT_GE(lines.size(), 2U) << hz.output();
  EXPECT_EQ(lines.front()["kind"], "window") << hz.output();
  EXPECT_EQ(lines.front()["contract_hz"], 2.0) << hz.output();
  const auto& window = lines[lines.size() - 2];
  EXPECT_EQ(window["kind"], "window") << hz.output();
  EXPECT_NEAR(window["rate_hz"].get<double>(), 2.0, 0.6) << hz.output();
  EXPECT_FALSE(window["min_interval_ms"].is_null()) << hz.output();
  EXPECT_EQ(lines.back()["kind"], "total") << hz.output();
  ChildProcess info({QUAD_TOOL, "topic", "info", "quad/system/heartbeat", "--wait", "1.5", "--json"},
                    {{"QUAD_DOMAIN_ID", "194"}, {"QUAD_TRANSPORT", "udp"}});
  ASSERT_EQ(info.wait(20s), 0) << info.output();
  const auto seen = nlohmann::json::parse(info.output(), nullptr, false);
  ASSERT_TRUE(seen.is_object()) << info.output();
  EXPECT_EQ(seen["owner"], "every module") << seen;
  ASSERT_EQ(seen["writers"].size(), 1U) << seen;
  EXPECT_EQ(seen["writers"][0]["participant"], "test_node") << seen;
  EXPECT_EQ(seen["writers"][0]["host"], "127.0.0.1") << seen;
}

}  // namespace

namespace {

TEST(NodeAndTools, TheManualHasAPagePerCommandThatManRendersAndBashCompletes)
{
  const auto dir = std::filesystem::temp_directory_path() / ("quad_manual_" + std::to_string(::getpid()));
  ChildProcess write({QUAD_TOOL, "--write-manual", dir.string()});
  ASSERT_EQ(write.wait(20s), 0) << write.output();
  for (const char* page : {"quad", "quad-launch", "quad-topic", "quad-topic-list", "quad-bag-info", "quad-so3-sample",
                           "quad-fault", "quad-campaign", "quad-plan", "quad-record", "quad-replay"}) {
    const auto file = dir / (std::string(page) + ".1");
    ASSERT_TRUE(std::filesystem::exists(file)) << page;
    ChildProcess man({"/usr/bin/env", "MANWIDTH=100", "man", "-l", file.string()});
    ASSERT_EQ(man.wait(20s), 0) << man.output();
    EXPECT_NE(man.output().find("NAME"), std::string::npos) << man.output();
    EXPECT_EQ(man.output().find("warning"), std::string::npos) << man.output();
  }
  // The options of a page are the command's own.
  ChildProcess list({"/usr/bin/env", "MANWIDTH=100", "man", "-l", (dir / "quad-topic-list.1").string()});
  ASSERT_EQ(list.wait(20s), 0);
  EXPECT_NE(list.output().find("--json"), std::string::npos) << list.output();
  const auto complete = [&](const std::string& words, int at) {
    ChildProcess bash({"/bin/bash", "-c",
                       "source " + (dir / "quad.bash").string() + "; COMP_WORDS=(" + words + "); COMP_CWORD=" +
                           std::to_string(at) + "; _quad; echo \"${COMPREPLY[*]}\""});
    bash.wait(10s);
    return bash.output();
  };
  EXPECT_EQ(complete("quad topic l", 2), "list\n");
  EXPECT_EQ(complete("quad topic list --j", 3), "--json\n");
  EXPECT_EQ(complete("quad la", 1), "launch\n");
  std::filesystem::remove_all(dir);
}

}  // namespace
