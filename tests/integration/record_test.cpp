// quad record against a live publisher: what it stores, and what a SIGKILL leaves.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

std::map<std::string, std::string> env(int domain) { return {{"QUAD_DOMAIN_ID", std::to_string(domain)}}; }

TEST(Record, EverySampleOfAReliableTopicIsRecordedWithItsLossFigures)
{
  const fs::path dir = quad::test::scratchDir("quad_record_all");
  const std::string file = (dir / "r.mcap").string();
  ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", file, "--duration", "8"}, env(190));
  ASSERT_TRUE(rec.waitForOutput("record: domain 190", 10s)) << rec.output();
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_HOLD}", "--count",
                    "40", "--rate", "20"},
                   env(190));
  ASSERT_EQ(pub.wait(30s), 0) << pub.output();
  ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  ChildProcess info({QUAD_TOOL, "bag", "info", file});
  ASSERT_EQ(info.wait(20s), 0) << info.output();
  EXPECT_NE(info.output().find("quad::msg::VehicleCommand"), std::string::npos) << info.output();
  EXPECT_NE(info.output().find("received 40 missing 0 duplicated 0 reordered 0 writers 1"), std::string::npos)
      << info.output();
  fs::remove_all(dir);
}

TEST(Record, ARecorderKilledWithSigkillLeavesItsCompleteChunksAndRecoverMakesTheFileWhole)
{
  const fs::path dir = quad::test::scratchDir("quad_record_kill");
  const std::string file = (dir / "k.mcap").string();
  ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", file, "--chunk-size", "512"}, env(191));
  ASSERT_TRUE(rec.waitForOutput("record: domain 191", 10s)) << rec.output();
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_HOLD}", "--count",
                    "60", "--rate", "30"},
                   env(191));
  ASSERT_EQ(pub.wait(30s), 0) << pub.output();
  rec.signal(SIGKILL);
  rec.wait(10s);
  ChildProcess info({QUAD_TOOL, "bag", "info", file});
  ASSERT_EQ(info.wait(20s), 1) << info.output();  // incomplete
  EXPECT_NE(info.output().find("INCOMPLETE"), std::string::npos) << info.output();
  ChildProcess recover({QUAD_TOOL, "bag", "recover", file, "-o", (dir / "whole.mcap").string()});
  ASSERT_EQ(recover.wait(20s), 0) << recover.output();
  ChildProcess again({QUAD_TOOL, "bag", "info", (dir / "whole.mcap").string()});
  ASSERT_EQ(again.wait(20s), 0) << again.output();
  EXPECT_NE(again.output().find("quad/system/command"), std::string::npos) << again.output();
  EXPECT_EQ(again.output().find("INCOMPLETE"), std::string::npos) << again.output();
  fs::remove_all(dir);
}

TEST(Record, ABadFileGetsAOneLineErrorNotACrash)
{
  const fs::path dir = quad::test::scratchDir("quad_record_bad");
  std::ofstream(dir / "bad.mcap") << "not a recording at all";
  ChildProcess info({QUAD_TOOL, "bag", "info", (dir / "bad.mcap").string()});
  ASSERT_EQ(info.wait(20s), 1) << info.output();
  EXPECT_NE(info.output().find("bad.mcap: not an MCAP file"), std::string::npos) << info.output();
  fs::remove_all(dir);
}

}  // namespace
