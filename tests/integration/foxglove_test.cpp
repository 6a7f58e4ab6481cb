// SPDX-License-Identifier: BSD-3-Clause
// The independent check: a quad recording read with Foxglove's own MCAP reader and OMG IDL
// decoder (npm packages, installed here with npm ci), every message decoded, and the decoded
// values equal to what quad topic echo printed for the same samples.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

const std::map<std::string, std::string> kEnv{{"QUAD_DOMAIN_ID", "196"}, {"QUAD_TRANSPORT", "udp"}};

/// npm ci of tests/foxglove into the build tree, once.
fs::path foxgloveTools()
{
  const fs::path dir = fs::path(QUAD_BUILD_DIR) / "foxglove";
  if (!fs::exists(dir / "node_modules/@mcap/core")) {
    fs::create_directories(dir);
    for (const char* f : {"package.json", "package-lock.json", "check.mjs"}) {
      fs::copy_file(fs::path(QUAD_SOURCE_DIR) / "tests/foxglove" / f, dir / f, fs::copy_options::overwrite_existing);
    }
    ChildProcess npm({QUAD_NPM, "ci", "--no-audit", "--no-fund", "--prefix", dir.string()});
    const auto status = npm.wait(300s);
    EXPECT_TRUE(status && *status == 0) << npm.output();
  }
  fs::copy_file(fs::path(QUAD_SOURCE_DIR) / "tests/foxglove/check.mjs", dir / "check.mjs",
                fs::copy_options::overwrite_existing);
  return dir;
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

}  // namespace
