// SPDX-License-Identifier: BSD-3-Clause
// quad campaign --slurm against a real single-node Slurm cluster (Debian's munged, slurmctld
// and slurmd, started here on ports of their own, as root): the runs submitted as a job
// array, one task cancelled on purpose, the campaign submitted again, which flies only that
// run, and every run done once. DDS domains 120 and 121 (the two tasks').
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "scratch.hpp"

namespace {

using namespace std::chrono_literals;
using quad::test::ChildProcess;
namespace fs = std::filesystem;

/// munged, slurmctld and slurmd in a folder of their own, stopped when it goes.
class SlurmCluster {
public:
  explicit SlurmCluster(const fs::path& dir) : dir_(dir)
  {
    fs::create_directories(dir_ / "munge");
    fs::permissions(dir_ / "munge", fs::perms::owner_all);
    fs::create_directories(dir_ / "state");
    fs::create_directories(dir_ / "spool");
    {
      std::ofstream key(dir_ / "munge/munge.key", std::ios::binary);
      std::ifstream random("/dev/urandom", std::ios::binary);
      char bytes[1024];
      random.read(bytes, sizeof bytes);
      key.write(bytes, sizeof bytes);
    }
    fs::permissions(dir_ / "munge/munge.key", fs::perms::owner_read);
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    std::string name = host;
    name = name.substr(0, name.find('.'));
    const int port = 17000 + 2 * static_cast<int>(::getpid() % 1000);
    std::ofstream(conf()) << "ClusterName=quadtest\nSlurmctldHost=" << name << "(127.0.0.1)\n"
                          << "SlurmctldPort=" << port << "\nSlurmdPort=" << port + 1 << "\n"
                          << "SlurmUser=root\nSlurmdUser=root\nAuthType=auth/munge\nCredType=cred/munge\n"
                          << "AuthInfo=socket=" << (dir_ / "munge/munge.sock").string() << "\n"
                          << "StateSaveLocation=" << (dir_ / "state").string() << "\n"
                          << "SlurmdSpoolDir=" << (dir_ / "spool").string() << "\n"
                          << "SlurmctldPidFile=" << (dir_ / "slurmctld.pid").string() << "\n"
                          << "SlurmdPidFile=" << (dir_ / "slurmd.pid").string() << "\n"
                          << "SlurmctldLogFile=" << (dir_ / "slurmctld.log").string() << "\n"
                          << "SlurmdLogFile=" << (dir_ / "slurmd.log").string() << "\n"
                          << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSchedulerType=sched/builtin\n"
                          << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\nMpiDefault=none\n"
                          << "ReturnToService=2\nJobAcctGatherType=jobacct_gather/none\n"
                          << "AccountingStorageType=accounting_storage/none\nSwitchType=switch/none\n"
                          << "NodeName=" << name << " NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN\n"
                          << "PartitionName=quad Nodes=" << name << " Default=YES MaxTime=INFINITE State=UP\n";
    munged_ = std::make_unique<ChildProcess>(std::vector<std::string>{
        QUAD_MUNGED, "-F", "-f", "--key-file=" + (dir_ / "munge/munge.key").string(),
        "--socket=" + (dir_ / "munge/munge.sock").string(), "--pid-file=" + (dir_ / "munge/munged.pid").string(),
        "--log-file=" + (dir_ / "munge/munged.log").string(), "--seed-file=" + (dir_ / "munge/seed").string()});
    for (auto until = std::chrono::steady_clock::now() + 10s;
         !fs::exists(dir_ / "munge/munge.sock") && std::chrono::steady_clock::now() < until;) {
      std::this_thread::sleep_for(50ms);
    }
    ctld_ = std::make_unique<ChildProcess>(std::vector<std::string>{QUAD_SLURMCTLD, "-D", "-f", conf().string()});
    slurmd_ = std::make_unique<ChildProcess>(std::vector<std::string>{QUAD_SLURMD, "-D", "-f", conf().string()},
                                             std::map<std::string, std::string>{{"SLURM_CONF", conf().string()}});
  }

  fs::path conf() const { return dir_ / "slurm.conf"; }
  std::map<std::string, std::string> env() const { return {{"SLURM_CONF", conf().string()}}; }

  /// The node is up and idle; false after `timeout`.
  bool waitIdle(std::chrono::seconds timeout)
  {
    for (auto until = std::chrono::steady_clock::now() + timeout; std::chrono::steady_clock::now() < until;) {
      ChildProcess sinfo({QUAD_SINFO, "-h", "-o", "%t"}, env());
      if (sinfo.wait(10s) == 0 && sinfo.output().find("idle") != std::string::npos) {
        return true;
      }
      std::this_thread::sleep_for(500ms);
    }
    return false;
  }

  std::string logs() const
  {
    return quad::test::readFile(dir_ / "slurmctld.log") + quad::test::readFile(dir_ / "slurmd.log");
  }

private:
  fs::path dir_;
  std::unique_ptr<ChildProcess> munged_, ctld_, slurmd_;
};

TEST(Slurm, ACancelledTaskIsFlownAgainByTheNextSubmissionAndEveryRunEndsDoneOnce)
{
  const fs::path dir = quad::test::scratchDir("quad_slurm");
  SlurmCluster cluster(dir / "cluster");
  ASSERT_TRUE(cluster.waitIdle(60s)) << cluster.logs();
  const std::string worlds = std::string(QUAD_SOURCE_DIR) + "/configs/worlds/";
  const fs::path runs = dir / "runs";
  const std::vector<std::string> command{QUAD_TOOL, "campaign", worlds + "open.yaml", worlds + "wall.yaml",
                                         "--slurm", "--domain", "120", "--log-dir", runs.string()};

  // The first submission: task 1 cancelled as soon as the job is there.
  ChildProcess first(command, cluster.env());
  ASSERT_TRUE(first.waitForOutput("submitted job ", 60s)) << first.output() << cluster.logs();
  const std::string out = first.output();
  const auto at = out.find("submitted job ") + 14;
  const std::string job = out.substr(at, out.find(':', at) - at);
  ChildProcess cancel({QUAD_SCANCEL, job + "_1"}, cluster.env());
  ASSERT_EQ(cancel.wait(30s), 0) << cancel.output();
  const auto status = first.wait(600s);
  ASSERT_TRUE(status) << first.output();
  EXPECT_EQ(*status, 1) << first.output();  // a run without a result fails the campaign
  auto j = nlohmann::json::parse(quad::test::readFile(runs / "campaign.json"), nullptr, false);
  ASSERT_TRUE(j.is_object()) << first.output();
  ASSERT_EQ(j["runs"].size(), 2U) << j.dump(2);
  EXPECT_EQ(j["runs"][0]["success"], true) << j.dump(2);
  EXPECT_EQ(j["runs"][1]["end"], "not flown") << j.dump(2);
  const fs::path kept = runs / "open-seed1" / "summary.json";
  ASSERT_TRUE(fs::exists(kept));
  const auto kept_time = fs::last_write_time(kept);

  // The second flies only the cancelled run, and the campaign ends with both, once each.
  ChildProcess second(command, cluster.env());
  const auto again = second.wait(600s);
  ASSERT_TRUE(again) << second.output();
  EXPECT_EQ(*again, 0) << second.output() << cluster.logs();
  EXPECT_NE(second.output().find("1 of 2 runs to fly, 1 with a result already"), std::string::npos) << second.output();
  j = nlohmann::json::parse(quad::test::readFile(runs / "campaign.json"), nullptr, false);
  ASSERT_TRUE(j.is_object()) << second.output();
  ASSERT_EQ(j["runs"].size(), 2U) << j.dump(2);
  for (const auto& r : j["runs"]) {
    EXPECT_EQ(r["success"], true) << j.dump(2);
  }
  EXPECT_EQ(fs::last_write_time(kept), kept_time) << "the run with a result was flown again";
  // the second job had the one task
  const std::string out2 = second.output();
  const auto at2 = out2.find("submitted job ");
  ASSERT_NE(at2, std::string::npos) << out2;
  const std::string job2 = out2.substr(at2 + 14, out2.find(':', at2 + 14) - at2 - 14);
  EXPECT_NE(out2.find("submitted job " + job2 + ": tasks 1 "), std::string::npos) << out2;
  EXPECT_TRUE(fs::exists(runs / "slurm" / (job2 + "_1.out")));
  EXPECT_FALSE(fs::exists(runs / "slurm" / (job2 + "_0.out")));
  if (!::testing::Test::HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
