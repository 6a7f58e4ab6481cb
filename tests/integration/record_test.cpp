// SPDX-License-Identifier: BSD-3-Clause
// quad record against a live publisher: what it stores, what a SIGKILL leaves, and its part in
// a lockstep run's start.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "module_wait.hpp"
#include "process.hpp"
#include "quad/bag/mcap.hpp"
#include "quad/common/payload_header.hpp"
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

TEST(Record, WithAVehicleOnlyThatVehiclesSamplesAreRecorded)
{
  // GIVEN commands for vehicles 1 and 2 on one domain (199), and a recorder of vehicle 2's
  const fs::path dir = quad::test::scratchDir("quad_record_vehicle");
  const std::string file = (dir / "r.mcap").string();
  ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", file, "--duration", "8", "--vehicle", "2"}, env(199));
  ASSERT_TRUE(rec.waitForOutput("record: domain 199", 10s)) << rec.output();
  ChildProcess one({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_HOLD}", "--count",
                    "30", "--rate", "20", "--vehicle", "1"},
                   env(199));
  ChildProcess two({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_LAND}", "--count",
                    "20", "--rate", "20", "--vehicle", "2"},
                   env(199));
  ASSERT_EQ(one.wait(30s), 0) << one.output();
  ASSERT_EQ(two.wait(30s), 0) << two.output();
  ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  // THEN the file holds vehicle 2's 20, none of vehicle 1's, and its loss figures count them alone
  const auto contents = quad::bag::readMcap(file);
  int of_two = 0;
  for (const auto& m : contents.messages) {
    const auto header = quad::common::payloadHeader(m.data);
    ASSERT_TRUE(header.has_value());
    EXPECT_EQ(header->vehicle_id, 2U);
    of_two += header->vehicle_id == 2 ? 1 : 0;
  }
  EXPECT_EQ(of_two, 20);
  ChildProcess info({QUAD_TOOL, "bag", "info", file});
  ASSERT_EQ(info.wait(20s), 0) << info.output();
  EXPECT_NE(info.output().find("received 20 missing 0 duplicated 0 reordered 0 writers 1"), std::string::npos)
      << info.output();
  fs::remove_all(dir);
}

TEST(Record, ARecordedLockstepRunWaitsForItsRecorderAndIsRecordedFromSimTimeZero)
{
  // GIVEN the plant of a recorded lockstep run (as quad launch starts it), and no recorder yet
  const int domain = 151;
  auto run_env = env(domain);
  run_env["QUAD_LOCKSTEP"] = "1";
  run_env["QUAD_LOCKSTEP_RECORDER"] = "1";
  const fs::path dir = quad::test::scratchDir("quad_record_lockstep");
  std::ofstream(dir / "plant.yaml") << "vehicle: " << QUAD_CONFIG_DIR << "/vehicles/x500.yaml\n"
                                    << "world: " << QUAD_CONFIG_DIR << "/worlds/demo.yaml\n"
                                    << "sim: {mode: lockstep, duration: 2.0}\nlockstep: {wait_for_command: false}\n";
  ChildProcess plant({QUAD_PLANT_NODE, "--config", (dir / "plant.yaml").string()}, run_env);
  ASSERT_TRUE(quad::test::waitForRunningModule(domain, "plant", 20s)) << plant.output();
  // THEN its clock waits at 0
  ChildProcess clock({QUAD_TOOL, "topic", "echo", "quad/sim/clock", "-n", "1", "--json", "--timeout", "10"}, run_env);
  ASSERT_EQ(clock.wait(15s), 0) << clock.output();
  const auto tick = nlohmann::json::parse(clock.output().substr(0, clock.output().find('\n')), nullptr, false);
  ASSERT_TRUE(tick.is_object()) << clock.output();
  EXPECT_EQ(tick["sim_ns"], 0) << clock.output();
  // WHEN the recorder starts, late
  const std::string file = (dir / "run.mcap").string();
  ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", file, "--duration", "8"}, run_env);
  // THEN the run goes on to its end, and the recording holds it from its first step: the
  // clock from 0, the first depth frame (0.1 s), and the recorder's report that let it go
  ASSERT_EQ(plant.wait(60s), 0) << plant.output();
  ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  const auto contents = quad::bag::readMcap(file);
  std::map<std::uint16_t, std::string> topics;
  for (const auto& ch : contents.channels) {
    topics[ch.id] = ch.topic;
  }
  std::map<std::string, std::vector<std::int64_t>> stamps;
  for (const auto& m : contents.messages) {
    if (const auto header = quad::common::payloadHeader(m.data)) {
      stamps[topics[m.channel_id]].push_back(header->stamp_ns);
    }
  }
  const auto& clocks = stamps["quad/sim/clock"];
  const auto& depth = stamps["quad/sim/depth"];
  ASSERT_FALSE(clocks.empty());
  ASSERT_FALSE(depth.empty());
  EXPECT_EQ(*std::min_element(clocks.begin(), clocks.end()), 0);
  EXPECT_GE(*std::max_element(clocks.begin(), clocks.end()), 1'996'000'000);
  EXPECT_EQ(*std::min_element(depth.begin(), depth.end()), 100'000'000);
  EXPECT_FALSE(stamps["quad/sim/lockstep"].empty());  // nothing else in this run reports
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
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

TEST(Record, RecordReplayRecordGivesIdenticalPayloadsAtTheRateAsked)
{
  const fs::path dir = quad::test::scratchDir("quad_record_roundtrip");
  const std::string first = (dir / "first.mcap").string();
  const std::string second = (dir / "second.mcap").string();
  {
    ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", first, "--duration", "6"}, env(192));
    ASSERT_TRUE(rec.waitForOutput("record: domain 192", 10s)) << rec.output();
    ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_LAND}",
                      "--count", "20", "--rate", "10"},
                     env(192));
    ASSERT_EQ(pub.wait(30s), 0) << pub.output();
    ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  }
  {
    ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", second, "--duration", "6"}, env(193));
    ASSERT_TRUE(rec.waitForOutput("record: domain 193", 10s)) << rec.output();
    ChildProcess replay({QUAD_TOOL, "replay", first, "--rate", "4"}, env(193));
    ASSERT_EQ(replay.wait(30s), 0) << replay.output();
    EXPECT_NE(replay.output().find("replay: 20 messages on 1 topics"), std::string::npos) << replay.output();
    ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  }
  const auto a = quad::bag::readMcap(first);
  const auto b = quad::bag::readMcap(second);
  ASSERT_EQ(a.messages.size(), 20U);
  ASSERT_EQ(b.messages.size(), a.messages.size());
  for (std::size_t i = 0; i < a.messages.size(); ++i) {
    EXPECT_EQ(b.messages[i].data, a.messages[i].data) << "message " << i;  // payloads untouched
  }
  // 19 intervals of 0.1 s, replayed 4x faster: about 0.475 s.
  const double span = static_cast<double>(b.messages.back().log_time - b.messages.front().log_time) * 1e-9;
  EXPECT_NEAR(span, 0.475, 0.2) << span;
  fs::remove_all(dir);
}

TEST(Record, SplitFilesTogetherHoldEveryMessageOnce)
{
  const fs::path dir = quad::test::scratchDir("quad_record_split");
  ChildProcess rec({QUAD_TOOL, "record", "-q", "-o", (dir / "s.mcap").string(), "--split-duration", "1", "--duration",
                    "7"},
                   env(195));
  ASSERT_TRUE(rec.waitForOutput("record: domain 195", 10s)) << rec.output();
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_HOLD}", "--count",
                    "40", "--rate", "10"},
                   env(195));
  ASSERT_EQ(pub.wait(30s), 0) << pub.output();
  ASSERT_EQ(rec.wait(30s), 0) << rec.output();
  std::vector<std::uint32_t> seqs;
  int parts = 0;
  for (int part = 0; fs::exists(dir / ("s_00" + std::to_string(part) + ".mcap")); ++part) {
    const auto c = quad::bag::readMcap(dir / ("s_00" + std::to_string(part) + ".mcap"));  // each part is whole
    ++parts;
    for (const auto& m : c.messages) {
      seqs.push_back(m.sequence);
    }
  }
  EXPECT_GE(parts, 3) << rec.output();
  ASSERT_EQ(seqs.size(), 40U);
  for (std::uint32_t i = 0; i < 40; ++i) {
    EXPECT_EQ(seqs[i], i + 1);
  }
  fs::remove_all(dir);
}

TEST(Record, AFullDiskIsReportedAndWhatWasWrittenBeforeCanBeRecovered)
{
  const std::map<std::string, std::string> udp = {{"QUAD_TRANSPORT", "udp"}};  // no shared-memory files
  const fs::path dir = quad::test::scratchDir("quad_record_full");
  // Full from the start: /dev/full refuses every write with ENOSPC.
  const fs::path no_space = dir / "no_space.mcap";
  fs::create_symlink("/dev/full", no_space);
  auto full_env = env(168);
  full_env.insert(udp.begin(), udp.end());
  ChildProcess full({QUAD_TOOL, "record", "-q", "-o", no_space.string(), "--duration", "5"}, full_env);
  ASSERT_EQ(full.wait(20s), 1) << full.output();
  EXPECT_NE(full.output().find(no_space.string() + ": cannot write: No space left on device"), std::string::npos)
      << full.output();

  // Full mid-recording: a file size limit fails a write (EFBIG) where a full disk would
  // (ENOSPC); the recorder must say so and stop, not hang or stop silently.
  const std::string file = (dir / "f.mcap").string();
  auto rec_env = env(169);
  rec_env.insert(udp.begin(), udp.end());
  ChildProcess rec({"/bin/sh", "-c", "trap '' XFSZ; ulimit -f 256; exec \"$0\" \"$@\"", QUAD_TOOL, "record", "-q",
                    "-o", file, "--chunk-size", "4096", "quad/system/command"},
                   rec_env);
  ASSERT_TRUE(rec.waitForOutput("record: domain 169", 10s)) << rec.output();
  ChildProcess pub({QUAD_TOOL, "topic", "pub", "quad/system/command", "{command_id: 1, kind: COMMAND_HOLD}", "--count",
                    "8000", "--rate", "1000"},
                   rec_env);
  ASSERT_EQ(pub.wait(60s), 0) << pub.output();  // about 800 KB of samples for 128 KiB of file
  const auto code = rec.wait(20s);
  ASSERT_TRUE(code) << "the recorder went on after its writes failed: " << rec.output();
  EXPECT_EQ(*code, 1) << rec.output();
  EXPECT_NE(rec.output().find(file + ": cannot write at byte"), std::string::npos) << rec.output();
  EXPECT_NE(rec.output().find("File too large"), std::string::npos) << rec.output();
  EXPECT_NE(rec.output().find("stopping"), std::string::npos) << rec.output();
  EXPECT_LE(fs::file_size(file), 256U * 1024U);  // ulimit -f counts blocks of 512 (dash) or 1024 bytes

  // Its complete chunks are intact: recovered, they hold the first samples, in order, none missing.
  const std::string whole = (dir / "whole.mcap").string();
  ChildProcess recover({QUAD_TOOL, "bag", "recover", file, "-o", whole});
  ASSERT_EQ(recover.wait(20s), 0) << recover.output();
  const auto c = quad::bag::readMcap(whole);
  ASSERT_GT(c.messages.size(), 100U) << recover.output();
  for (std::size_t i = 0; i < c.messages.size(); ++i) {
    ASSERT_EQ(c.messages[i].sequence, i + 1) << "message " << i;
  }
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
