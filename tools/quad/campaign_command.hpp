// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad campaign [WORLDS...] [--file FILE] [--set AXIS=V1,V2...] [--seeds N] [-j N]`: flies the
/// product of worlds, axes and seeds, N runs at a time, prints a table, writes JSON; exits
/// non-zero when any run failed.

#include <optional>
#include <string>
#include <vector>

namespace quad::tools {

struct CampaignCommandOptions {
  std::vector<std::string> worlds;
  std::optional<std::string> file;     ///< a campaign file (campaign_file.hpp); the options below add to it or replace its values
  std::vector<std::string> axes;       ///< MODULE:KEY=V1,V2,... or world:TYPE.KEY=...
  std::optional<int> seeds;            ///< default: the file's, else 1
  std::optional<int> jobs;             ///< default: the file's, else 1
  std::optional<std::string> manifest; ///< default: the file's, else bringup/demo.yaml
  std::optional<int> domain;           ///< default: $QUAD_DOMAIN_ID, else 0
  std::optional<std::string> json;     ///< default: <dir>/campaign.json
  std::optional<std::string> dir;      ///< default: log/campaign-<time>-<pid>
  std::optional<double> wall_timeout_s;  ///< default: the file's, else 600 s
  std::optional<std::string> state;    ///< estimate | truth; default: the file's, else the manifest's
  std::optional<std::string> layout;   ///< distributed | composed; default: the file's, else the manifest's
  bool no_record = false;              ///< no recording (nor run report) per run; default: the file's, else record
  bool check = false;                  ///< check everything and exit
  bool slurm = false;                  ///< submit the runs to a Slurm cluster as one job array
  std::vector<std::string> sbatch_args;  ///< more sbatch options, with --slurm
  std::optional<int> task;             ///< fly run N of the product alone (what each Slurm task runs)
};

/// 0 when every run succeeded, 1 when any failed, 2 for bad input, 130 when stopped by a signal.
int campaign(const CampaignCommandOptions& options);

}  // namespace quad::tools
