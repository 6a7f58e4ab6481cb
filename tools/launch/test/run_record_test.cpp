// SPDX-License-Identifier: BSD-3-Clause
// run.json: what programs read of a run, whole at every moment.
#include "quad/launch/run_record.hpp"

#include <gtest/gtest.h>

#include <set>

#include <nlohmann/json.hpp>

#include "scratch.hpp"

namespace quad::launch {
namespace {

RunRecord twoModules()
{
  RunRecord r;
  r.manifest = "bringup/demo.yaml";
  r.domain = 42;
  r.order = {"plant", "mapping"};
  r.modules["mapping"] = {"mapping", "local"};
  r.modules["plant"] = {"plant", "sim"};
  return r;
}

TEST(RunRecord, ListsModulesInTheManifestsOrderWithTheirPhase)
{
  RunRecord r = twoModules();
  r.modules["plant"].phase = ModulePhase::kRunning;
  r.modules["plant"].pid = 1234;
  r.modules["plant"].starts = 1;
  const auto j = nlohmann::ordered_json::parse(toJson(r));
  EXPECT_EQ(j["manifest"], "bringup/demo.yaml");
  EXPECT_EQ(j["domain"], 42);
  EXPECT_EQ(j["phase"], "starting");
  EXPECT_TRUE(j["exit_code"].is_null());  // not ended yet
  ASSERT_EQ(j["modules"].size(), 2U);
  EXPECT_EQ(j["modules"].begin().key(), "plant");
  EXPECT_EQ(j["modules"]["plant"]["phase"], "running");
  EXPECT_EQ(j["modules"]["plant"]["host"], "sim");
  EXPECT_EQ(j["modules"]["plant"]["pid"], 1234);
  EXPECT_EQ(j["modules"]["mapping"]["phase"], "waiting");
  EXPECT_EQ(j["modules"]["mapping"]["starts"], 0);
}

TEST(RunRecord, AnEndedRunHasItsExitCodeFailureAndStopOrder)
{
  RunRecord r = twoModules();
  r.phase = RunPhase::kEnded;
  r.exit_code = 1;
  r.failure = "mapping failed (killed by SIGKILL) after 1 restarts";
  r.modules["mapping"].phase = ModulePhase::kFailed;
  r.modules["mapping"].restarts = 1;
  r.modules["mapping"].last_exit = "killed by SIGKILL";
  r.modules["plant"].phase = ModulePhase::kStopped;
  r.stopped_order = {"plant"};
  const auto j = nlohmann::json::parse(toJson(r));
  EXPECT_EQ(j["phase"], "ended");
  EXPECT_EQ(j["exit_code"], 1);
  EXPECT_EQ(j["failure"], r.failure);
  EXPECT_EQ(j["modules"]["mapping"]["phase"], "failed");
  EXPECT_EQ(j["modules"]["mapping"]["restarts"], 1);
  EXPECT_EQ(j["modules"]["mapping"]["last_exit"], "killed by SIGKILL");
  EXPECT_EQ(j["stopped_order"], nlohmann::json::array({"plant"}));
}

TEST(RunRecord, EveryPhaseHasItsOwnName)
{
  const ModulePhase all[] = {ModulePhase::kWaiting, ModulePhase::kStarting, ModulePhase::kRunning,
                             ModulePhase::kRestarting, ModulePhase::kExited, ModulePhase::kFailed,
                             ModulePhase::kStopped};
  std::set<std::string_view> names;
  for (const auto p : all) {
    names.insert(toString(p));
  }
  EXPECT_EQ(names.size(), std::size(all));
}

TEST(RunRecord, IsReplacedWholeAndLeavesNoPartialFile)
{
  const auto dir = test::scratchDir("quad_run_record");
  RunRecord r = twoModules();
  ASSERT_TRUE(writeRunRecord(dir / "run.json", r));
  r.phase = RunPhase::kRunning;
  ASSERT_TRUE(writeRunRecord(dir / "run.json", r));
  EXPECT_EQ(nlohmann::json::parse(test::readFile(dir / "run.json"))["phase"], "running");
  EXPECT_FALSE(std::filesystem::exists(dir / "run.json.partial"));
  std::filesystem::remove_all(dir);
}

TEST(RunRecord, AFolderThatIsNotThereIsReportedNotIgnored)
{
  EXPECT_FALSE(writeRunRecord("/nonexistent/quad/run.json", twoModules()));
}

}  // namespace
}  // namespace quad::launch
