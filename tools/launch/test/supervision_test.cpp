// SPDX-License-Identifier: BSD-3-Clause
// The launcher's process side: supervision, stale shared memory, commands for remote hosts.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <thread>

#include "quad/launch/hosts.hpp"
#include "scratch.hpp"
#include "quad/launch/shm.hpp"
#include "quad/launch/supervisor.hpp"

namespace quad::launch {
namespace {

namespace fs = std::filesystem;

/// Pumps until `name` exits or 5 s pass; its status, or -1.
int waitExit(Supervisor& s, const std::string& name)
{
  for (int i = 0; i < 100; ++i) {
    for (const auto& e : s.pump(50)) {
      if (e.name == name) {
        return e.status;
      }
    }
  }
  return -1;
}

TEST(Supervisor, OutputIsKeptPerProcessAndExitsAreReported)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_output");
  Supervisor s(dir, nullptr, false);
  s.start("talker", {"sh", "-c", "echo one; echo two >&2; printf three; exit 3"}, {});
  EXPECT_EQ(waitExit(s, "talker"), 3);
  EXPECT_FALSE(s.running("talker"));
  const std::string log = quad::test::readFile(dir / "talker.log");
  for (const char* line : {"\none\n", "\ntwo\n", "\nthree\n", "ended: exit 3"}) {
    EXPECT_NE(log.find(line), std::string::npos) << line << " in\n" << log;
  }
  fs::remove_all(dir);
}

TEST(ModuleTunables, HugePagesAreAskedUnlessTheGivenTunablesSayOtherwise)
{
  EXPECT_EQ(moduleTunables(""), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(moduleTunables("glibc.malloc.arena_max=2"), "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  EXPECT_EQ(moduleTunables("glibc.malloc.hugetlb=0"), "glibc.malloc.hugetlb=0");
  EXPECT_EQ(moduleTunables(moduleTunables("")), moduleTunables(""));  // a launch within a launch adds nothing
}

TEST(Supervisor, EnvironmentIsPassed)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_env");
  Supervisor s(dir, nullptr, false);
  s.start("env", {"sh", "-c", "echo domain=$QUAD_DOMAIN_ID"}, {{"QUAD_DOMAIN_ID", "77"}});
  EXPECT_EQ(waitExit(s, "env"), 0);
  EXPECT_NE(quad::test::readFile(dir / "env.log").find("domain=77"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Supervisor, AProcessIsChargedTheCpuTimeItRanNotTheTimeItWaitedAndARestartAddsUp)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_cpu");
  Supervisor s(dir, nullptr, false);
  s.start("sleeper", {"sleep", "0.5"}, {});
  EXPECT_FALSE(s.cpuSeconds("sleeper"));  // nothing known while it runs
  EXPECT_EQ(waitExit(s, "sleeper"), 0);
  ASSERT_TRUE(s.cpuSeconds("sleeper"));
  EXPECT_LT(*s.cpuSeconds("sleeper"), 0.1);  // it waited half a second

  const auto busy = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    s.start("busy", {"sh", "-c", "i=0; while [ $i -lt 100000 ]; do i=$((i + 1)); done"}, {});
    EXPECT_EQ(waitExit(s, "busy"), 0);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const double wall = busy();
  ASSERT_TRUE(s.cpuSeconds("busy"));
  const double first = *s.cpuSeconds("busy");
  EXPECT_GT(first, 0.05);  // it counted
  EXPECT_LE(first, wall);  // one thread: never more than the time it took
  busy();
  EXPECT_GT(*s.cpuSeconds("busy"), first + 0.05);  // the second instance's time is added
  fs::remove_all(dir);
}

TEST(Supervisor, AProcessIsChargedThePeakMemoryItHeldAndARestartKeepsTheLargest)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_rss");
  Supervisor s(dir, nullptr, false);
  // dd reads one block into a buffer of that size: the block's memory is touched, so resident.
  const auto copy = [&](const std::string& block) {
    s.start("copy", {"dd", "if=/dev/zero", "of=/dev/null", "bs=" + block, "count=1"}, {});
    EXPECT_EQ(waitExit(s, "copy"), 0);
  };
  EXPECT_FALSE(s.maxResidentMiB("copy"));  // nothing known before one ended
  copy("64M");
  ASSERT_TRUE(s.maxResidentMiB("copy"));
  EXPECT_GE(*s.maxResidentMiB("copy"), 64.0);
  EXPECT_LT(*s.maxResidentMiB("copy"), 128.0);
  copy("1M");  // a smaller second instance: the peak stays the first's
  EXPECT_GE(*s.maxResidentMiB("copy"), 64.0);
  copy("160M");
  EXPECT_GE(*s.maxResidentMiB("copy"), 160.0);
  fs::remove_all(dir);
}

TEST(Supervisor, AProcessIsChargedTheTimesItWaitedAndARestartAddsThem)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_waits");
  Supervisor s(dir, nullptr, false);
  // Five sleeps: the shell waits for each, each sleep waits its time out.
  const auto sleeper = [&] {
    s.start("sleeper", {"sh", "-c", "for i in 1 2 3 4 5; do sleep 0.02; done"}, {});
    EXPECT_EQ(waitExit(s, "sleeper"), 0);
  };
  EXPECT_FALSE(s.waits("sleeper"));  // nothing known before one ended
  sleeper();
  ASSERT_TRUE(s.waits("sleeper"));
  const std::uint64_t first = *s.waits("sleeper");
  EXPECT_GE(first, 5U);
  sleeper();
  EXPECT_GE(*s.waits("sleeper"), first + 5U);  // the second instance's waits are added
  fs::remove_all(dir);
}

TEST(Supervisor, StopEscalatesToSigkillAfterTheGracePeriod)
{
  const fs::path dir = quad::test::scratchDir("quad_supervisor_stop");
  Supervisor s(dir, nullptr, false);
  s.start("stubborn", {"sh", "-c", "trap '' TERM; echo ready; while true; do sleep 0.05; done"}, {});
  for (int i = 0; i < 100 && quad::test::readFile(dir / "stubborn.log").find("\nready\n") == std::string::npos; ++i) {
    s.pump(50);
  }
  const auto status = s.stop("stubborn", 0.3);
  ASSERT_TRUE(status);
  EXPECT_EQ(*status, 128 + SIGKILL);
  s.start("polite", {"sleep", "30"}, {});
  const auto polite = s.stop("polite", 5.0);
  ASSERT_TRUE(polite);
  EXPECT_EQ(*polite, 128 + SIGTERM);
  fs::remove_all(dir);
}

TEST(SharedMemory, OnlyUnheldOldFastDdsFilesAreStale)
{
  const fs::path dir = quad::test::scratchDir("quad_shm");
  for (const char* f : {"fastrtps_aaaa", "fastrtps_aaaa_el", "fastrtps_bbbb", "fastrtps_bbbb_el", "other_file"}) {
    std::ofstream(dir / f) << "x";
  }
  // bbbb is held open, like a running participant's segment.
  std::ifstream held(dir / "fastrtps_bbbb");
  const auto old = fs::file_time_type::clock::now() - std::chrono::minutes(1);
  for (const auto& e : fs::directory_iterator(dir)) {
    fs::last_write_time(e.path(), old);
  }
  std::ofstream(dir / "fastrtps_cccc") << "new";  // too young to judge
  auto stale = staleSharedMemory(dir, std::chrono::seconds(5));
  std::sort(stale.begin(), stale.end());
  ASSERT_EQ(stale.size(), 2U);
  EXPECT_EQ(stale[0].filename(), "fastrtps_aaaa");
  EXPECT_EQ(stale[1].filename(), "fastrtps_aaaa_el");
  const auto cleaned = cleanStaleSharedMemory(dir, std::chrono::seconds(5));
  EXPECT_EQ(cleaned.files, 2);
  EXPECT_TRUE(fs::exists(dir / "fastrtps_bbbb_el"));
  EXPECT_TRUE(fs::exists(dir / "other_file"));
  fs::remove_all(dir);
}

TEST(HostNetwork, SshCommandsCarryTheEnvironmentQuotedAndMoveTheCheckout)
{
  Manifest m;
  m.file = "/src/quad/bringup/m.yaml";
  m.hosts = {Host{"far", HostKind::kSsh, "pilot@10.1.2.3", 2222, "/opt/quad", {"-i", "/k"}}};
  HostNetwork net(m, "1");
  EXPECT_EQ(net.address("far"), "10.1.2.3");
  const auto argv = net.command(m.hosts[0], {"/src/quad/build/x", "--set", "name=it's"}, {{"QUAD_DOMAIN_ID", "5"}});
  const std::vector<std::string> expected{
      "ssh", "-tt", "-o", "BatchMode=yes", "-p", "2222", "-i", "/k", "pilot@10.1.2.3", "--", "env", "'QUAD_DOMAIN_ID=5'",
      "'/opt/quad/build/x'", "'--set'", "'name=it'\\''s'"};
  EXPECT_EQ(argv, expected);
}

}  // namespace
}  // namespace quad::launch
