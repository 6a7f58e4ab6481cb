// SPDX-License-Identifier: BSD-3-Clause
#include "campaign_command.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "quad/campaign/campaign.hpp"
#include "quad/campaign/campaign_file.hpp"
#include "quad/campaign/campaign_report.hpp"
#include "quad/campaign/slurm.hpp"
#include "quad/common/params.hpp"
#include "quad/dds/participant.hpp"
#include "quad/launch/run.hpp"
#include "quad/runtime/node.hpp"

namespace quad::tools {

namespace fs = std::filesystem;

namespace {

/// The campaign's options: the file's, then the command line's over them.
campaign::CampaignOptions campaignOptions(const CampaignCommandOptions& options)
{
  campaign::CampaignOptions c;
  campaign::CampaignFile file;
  if (options.file) {
    file = campaign::readCampaignFile(*options.file);
  }
  std::vector<std::string> problems;
  c.quad = fs::read_symlink("/proc/self/exe");
  if (options.manifest) {
    c.manifest = fs::absolute(launch::findManifest(*options.manifest, common::layout()));
  } else {
    c.manifest = file.manifest.value_or(common::layout().data / "bringup" / "demo.yaml");
  }
  c.worlds = file.worlds;
  for (const auto& w : options.worlds) {
    if (!fs::is_regular_file(w)) {
      problems.push_back(w + ": no such world file");
    }
    c.worlds.push_back(fs::absolute(w).lexically_normal());
  }
  if (c.worlds.empty()) {
    problems.emplace_back("no world to fly: give world files, or a campaign file with worlds");
  }
  c.axes = file.axes;
  for (const auto& a : options.axes) {
    try {
      campaign::Axis axis = campaign::parseAxis(a, "--set");
      // an axis the file has too: the command line's values replace the file's
      const auto same = std::find_if(c.axes.begin(), c.axes.end(), [&](const campaign::Axis& x) { return x.key == axis.key; });
      if (same != c.axes.end()) {
        same->values = axis.values;
      } else {
        c.axes.push_back(std::move(axis));
      }
    } catch (const common::ConfigError& e) {
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  c.seeds = options.seeds.value_or(file.seeds.value_or(1));
  c.jobs = options.jobs.value_or(file.jobs.value_or(1));
  c.wall_timeout_s = options.wall_timeout_s.value_or(file.wall_timeout_s.value_or(600.0));
  c.state = options.state.value_or(file.state.value_or(""));
  c.layout = options.layout.value_or(file.layout.value_or(""));
  c.record = !options.no_record && file.record.value_or(true);
  c.domain = options.domain ? *options.domain : dds::optionsFromEnvironment("quad_campaign").domain_id;
  if (c.domain + c.jobs - 1 > 232) {
    problems.push_back(fmt::format("-j {} from domain {}: the runs flying together take domains {} to {}; DDS has 0 to 232",
                                   c.jobs, c.domain, c.domain, c.domain + c.jobs - 1));
  }
  c.dir = fs::absolute(options.dir ? fs::path(*options.dir) : fs::path("log") / launch::runFolderName("campaign"));
  if (!problems.empty()) {
    throw common::ConfigError(problems);
  }
  return c;
}

/// `--task N`: run N of the product alone, as a cluster's task flies it; the submitter checked
/// the campaign. Exits with the launcher's status.
int flyTask(const campaign::CampaignOptions& c, int task)
{
  const auto plan = campaign::planRuns(c.worlds, c.axes, c.seeds);
  if (task < 0 || static_cast<std::size_t>(task) >= plan.size()) {
    std::fprintf(stderr, "campaign: --task %d: the campaign has runs 0 to %zu\n", task, plan.size() - 1);
    return launch::kExitInvalid;
  }
  const campaign::CampaignRun r = campaign::flyRun(c, plan[static_cast<std::size_t>(task)], static_cast<std::size_t>(task));
  std::printf("campaign: task %d, %s: %s in %.0f s wall%s\n", task, r.name.c_str(), r.success ? "ok" : "FAILED", r.wall_s,
              r.failure.empty() ? "" : (" (" + r.failure + ")").c_str());
  return r.exit_status;
}

}  // namespace

int campaign(const CampaignCommandOptions& options)
{
  runtime::SignalWatcher signals;  // before any thread exists
  campaign::CampaignOptions c;
  try {
    c = campaignOptions(options);
    if (options.task) {
      c.stop = [&signals] { return signals.received() != 0; };
      return flyTask(c, *options.task);
    }
    const auto problems = campaign::checkCampaign(c);
    if (!problems.empty()) {
      throw common::ConfigError(problems);
    }
  } catch (const common::ConfigError& e) {
    for (const auto& p : e.problems()) {
      std::fprintf(stderr, "campaign: %s\n", p.c_str());
    }
    std::fprintf(stderr, "campaign: refusing to start\n");
    return launch::kExitInvalid;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campaign: %s\n", e.what());
    return launch::kExitInvalid;
  }
  const std::size_t total = campaign::planRuns(c.worlds, c.axes, c.seeds).size();
  if (options.check) {
    std::printf("campaign: ok (%zu runs)\n", total);
    return 0;
  }
  c.stop = [&signals] { return signals.received() != 0; };
  fs::create_directories(c.dir);
  if (options.slurm) {
    std::printf("campaign: %zu worlds x %zu axes x %d seeds = %zu runs, on Slurm, in %s (a folder every node shares)\n",
                c.worlds.size(), c.axes.size(), c.seeds, total, c.dir.string().c_str());
  } else {
    std::printf("campaign: %zu worlds x %zu axes x %d seeds = %zu runs, %d at a time, in %s\n", c.worlds.size(),
                c.axes.size(), c.seeds, total, c.jobs, c.dir.string().c_str());
  }
  std::fflush(stdout);
  std::size_t ended = 0;
  std::vector<campaign::CampaignRun> runs;
  if (options.slurm) {
    try {
      runs = campaign::runOnSlurm(c, {options.sbatch_args}, [](const std::string& line) {
        std::printf("campaign: %s\n", line.c_str());
        std::fflush(stdout);
      });
    } catch (const std::exception& e) {
      std::fprintf(stderr, "campaign: %s\n", e.what());
      return launch::kExitFailed;
    }
    ended = static_cast<std::size_t>(std::count_if(runs.begin(), runs.end(), [](const campaign::CampaignRun& r) {
      return r.end != "not flown";
    }));
  } else {
    runs = campaign::runCampaign(c, [&](const campaign::CampaignRun& r) {
      ++ended;
      std::printf("campaign: [%zu/%zu] %s: %s in %.0f s wall%s\n", ended, total, r.name.c_str(),
                  r.success ? "ok" : (r.end == "interrupted" ? "interrupted" : "FAILED"), r.wall_s,
                  r.failure.empty() ? "" : (" (" + r.failure + ")").c_str());
      std::fflush(stdout);
    });
  }
  std::printf("%s", campaign::table(runs, c.axes).c_str());
  const fs::path json = options.json ? fs::path(*options.json) : c.dir / "campaign.json";
  std::ofstream out(json);
  out << campaign::toJson(runs, c.axes);
  if (!out) {
    std::fprintf(stderr, "campaign: cannot write %s\n", json.string().c_str());
    return launch::kExitFailed;
  }
  std::printf("campaign: %s\n", json.string().c_str());
  try {
    std::printf("campaign: report in %s\n", campaign::writeCampaignReport(runs, c.axes, c.dir).string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campaign: no report: %s\n", e.what());
  }
  if (signals.received() != 0) {
    const auto interrupted = std::count_if(runs.begin(), runs.end(), [](const campaign::CampaignRun& r) {
      return r.end == "interrupted";
    });
    std::fprintf(stderr, "campaign: stopped by a signal: %zu of %zu runs flown, %zd interrupted\n",
                 ended - static_cast<std::size_t>(interrupted), total, interrupted);
    return 128 + signals.received();
  }
  const bool all = std::all_of(runs.begin(), runs.end(), [](const campaign::CampaignRun& r) { return r.success; });
  return all ? 0 : launch::kExitFailed;
}

}  // namespace quad::tools
