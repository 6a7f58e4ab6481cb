// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A campaign on a Slurm cluster (`quad campaign --slurm`): its runs submitted as one job
/// array, a task per run, each task `quad campaign --file <campaign>/campaign.yaml --task N`
/// on whichever node Slurm gives it; the results gathered from the runs' folders, which must
/// be on a filesystem every node shares (the campaign's folder and the quad command at the
/// same paths everywhere). Resumable: a run whose folder holds its result is not flown again.

#include <functional>
#include <string>
#include <vector>

#include "quad/campaign/campaign.hpp"

namespace quad::campaign {

struct SlurmOptions {
  std::vector<std::string> sbatch_args;  ///< more sbatch options ("--partition=quad", "--time=30")
  std::string sbatch = "sbatch";         ///< the programs, looked up on PATH
  std::string scancel = "scancel";
};

/// Submits every run of the product that has no result yet (storedResult) as one job array,
/// waits for it (`sbatch --wait`), and gathers every run's result: those without one after the
/// job (a task that failed, was cancelled, or its node lost) say so, with their task's output
/// file. `say` hears what is submitted; options.stop cancels the job (scancel).
/// Throws std::runtime_error when sbatch cannot submit, with its output.
std::vector<CampaignRun> runOnSlurm(const CampaignOptions& options, const SlurmOptions& slurm,
                                    const std::function<void(const std::string&)>& say = {});

/// "0-3,5,7-9": indices as a job array's --array.
std::string arrayRanges(const std::vector<std::size_t>& indices);

}  // namespace quad::campaign
