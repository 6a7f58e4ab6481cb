// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad campaign`: flies a set of worlds (and seeds) one after another, each a `quad launch`
/// of one manifest in lockstep, and gathers their summaries into one table and one JSON.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace quad::campaign {

struct CampaignOptions {
  std::filesystem::path quad;       ///< the quad command that launches each run
  std::filesystem::path manifest;   ///< flown in every world
  std::vector<std::filesystem::path> worlds;
  int seeds = 1;                    ///< seeds 1 ... seeds for each world
  int domain = 0;                   ///< the DDS domain of every run (they run one at a time)
  std::filesystem::path dir;        ///< a folder per run (logs, summary.json)
  double wall_timeout_s = 600.0;    ///< a run still going after this fails
  std::string state;                ///< `quad launch --state`: estimate or truth; empty: the manifest's
  std::string layout;               ///< `quad launch --layout`: distributed or composed; empty: the manifest's
};

/// One run, from its summary and exit status.
struct CampaignRun {
  std::string world;                ///< the file's stem
  std::uint64_t seed = 1;
  int exit_status = -1;
  bool success = false;
  std::string end;                  ///< the summary's: success, failed, no_path, unfinished ("" without one)
  std::string failure;              ///< why, in words
  int collisions = 0;
  double path_length_m = 0.0;
  std::optional<double> optimum_m;
  std::optional<double> flown_over_optimum;
  double min_clearance_m = 0.0;
  std::optional<double> time_to_goal_s;     ///< from the mission's start (summary's time_to_goal_s)
  std::optional<double> average_speed_mps;  ///< over that time
  double top_speed_mps = 0.0;
  int replans = 0;                  ///< path versions the planner published
  double sim_s = 0.0;
  double wall_s = 0.0;
  std::string state;                ///< what the run flew on (the summary's `state`)
  std::optional<double> estimate_rms_m;  ///< the estimate's position error, RMS (summary's estimate)
  std::optional<double> estimate_nees;   ///< its mean position NEES (3 for a consistent filter)
  std::optional<double> depth_to_command_max_s;  ///< the summary's: the slowest reaction to a depth frame
};

/// The runs' summaries read back: a summary.json as `quad launch --summary` writes it.
/// Throws std::runtime_error naming the file when it is missing or not such a summary.
CampaignRun readRun(const std::filesystem::path& summary, const std::string& world, std::uint64_t seed,
                    int exit_status);

/// Flies every world with every seed, in order; `progress` hears each run as it ends.
std::vector<CampaignRun> runCampaign(const CampaignOptions& options,
                                     const std::function<void(const CampaignRun&)>& progress = {});

/// A table for people: a row a run and a last row of totals.
std::string table(const std::vector<CampaignRun>& runs);
/// The same as JSON: {"runs": [...], "succeeded": n, "runs_total": n}.
std::string toJson(const std::vector<CampaignRun>& runs);

}  // namespace quad::campaign
