// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/slurm.hpp"

#include <poll.h>

#include <csignal>
#include <fstream>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "quad/campaign/campaign_file.hpp"
#include "quad/process/run.hpp"
#include "quad/process/shell_quote.hpp"
#include "quad/process/spawn.hpp"

namespace quad::campaign {

namespace fs = std::filesystem;

std::string arrayRanges(const std::vector<std::size_t>& indices)
{
  std::string out;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) {
      ++j;
    }
    out += (out.empty() ? "" : ",") + (j == i ? std::to_string(indices[i])
                                               : fmt::format("{}-{}", indices[i], indices[j]));
    i = j + 1;
  }
  return out;
}

std::vector<CampaignRun> runOnSlurm(const CampaignOptions& options, const SlurmOptions& slurm,
                                    const std::function<void(const std::string&)>& say)
{
  const auto tell = [&](const std::string& line) {
    if (say) {
      say(line);
    }
  };
  const std::vector<PlannedRun> plan = planRuns(options.worlds, options.axes, options.seeds);
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (!storedResult(options, plan[i])) {
      pending.push_back(i);
    }
  }
  tell(fmt::format("{} of {} runs to fly, {} with a result already", pending.size(), plan.size(),
                   plan.size() - pending.size()));
  std::string job;
  if (!pending.empty()) {
    const fs::path file = options.dir / "campaign.yaml";
    std::ofstream(file) << "# written by quad campaign --slurm: what each task flies\n" << campaignFileText(options);
    const fs::path script = options.dir / "slurm_task.sh";
    const auto word = [](const fs::path& p) { return process::shellQuote(p.string()); };
    std::ofstream(script) << "#!/bin/sh\n# One run of the campaign a Slurm task: run number $SLURM_ARRAY_TASK_ID of its product.\n"
                          << "exec " << word(options.quad) << " campaign --file " << word(file) << " --log-dir "
                          << word(options.dir) << " --domain " << options.domain << " --task \"$SLURM_ARRAY_TASK_ID\"\n";
    fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::others_read);
    fs::create_directories(options.dir / "slurm");
    std::vector<std::string> argv{slurm.sbatch, "--parsable", "--wait", "--array=" + arrayRanges(pending),
                                  "--job-name=quad-campaign", "--output=" + (options.dir / "slurm" / "%A_%a.out").string(),
                                  "--chdir=" + options.dir.string()};
    argv.insert(argv.end(), slurm.sbatch_args.begin(), slurm.sbatch_args.end());
    argv.push_back(script.string());
    process::Spawned sbatch(argv);
    std::string output;
    std::optional<int> status;
    bool cancelled = false;
    while (!(status = sbatch.poll())) {
      pollfd p{sbatch.outputFd(), POLLIN, 0};
      ::poll(&p, 1, 200);
      sbatch.readOutput(output);
      if (job.empty() && output.find('\n') != std::string::npos) {
        job = output.substr(0, output.find_first_of(";\n"));  // --parsable: "JOBID[;CLUSTER]"
        tell(fmt::format("submitted job {}: tasks {} (their output in {})", job, arrayRanges(pending),
                         (options.dir / "slurm").string()));
      }
      if (!cancelled && options.stop && options.stop() && !job.empty()) {
        cancelled = true;
        tell("cancelling job " + job);
        (void)process::run({slurm.scancel, job});
      }
    }
    sbatch.readOutput(output);
    if (job.empty()) {
      throw std::runtime_error(fmt::format("{} could not submit the campaign ({}): {}", slurm.sbatch,
                                           process::describeStatus(*status), output));
    }
  }
  std::vector<CampaignRun> runs;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (auto r = storedResult(options, plan[i])) {
      runs.push_back(std::move(*r));
      continue;
    }
    CampaignRun r = unflownRun(plan[i]);
    r.end = "not flown";
    r.failure = fmt::format("no result: its task {}_{} failed or was cancelled (slurm/{}_{}.out)", job, i, job, i);
    runs.push_back(std::move(r));
  }
  return runs;
}

}  // namespace quad::campaign
