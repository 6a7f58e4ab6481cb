// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad campaign`: flies the product of worlds, sweep axes (sweep.hpp) and seeds, each run a
/// `quad launch` of one manifest in lockstep, N at a time, and gathers their summaries into
/// one table and one JSON.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "quad/campaign/sweep.hpp"

namespace quad::campaign {

struct CampaignOptions {
  std::filesystem::path quad;       ///< the quad command that launches each run
  std::filesystem::path manifest;   ///< flown in every world
  std::vector<std::filesystem::path> worlds;
  int seeds = 1;                    ///< seeds 1 ... seeds for each world
  std::vector<Axis> axes;           ///< swept beyond worlds and seeds
  int jobs = 1;                     ///< runs flown at once
  /// The DDS domain of the first of the runs flown at once; the one in slot k of `jobs` flies
  /// on domain + k, so no two runs flying together share a domain (or its ports).
  int domain = 0;
  std::filesystem::path dir;        ///< a folder per run (logs, summary.json)
  double wall_timeout_s = 600.0;    ///< a run still going after this fails
  std::string state;                ///< `quad launch --state`: estimate or truth; empty: the manifest's
  std::string layout;               ///< `quad launch --layout`: distributed or composed; empty: the manifest's
  bool record = true;               ///< false: `quad launch --no-record` (no recording, no run report)
  /// Polled while runs fly: once true, no run starts and the flying ones are interrupted
  /// (SIGINT, as Ctrl-C would; after a grace, killed).
  std::function<bool()> stop;
};

/// One run, from its summary and exit status.
struct CampaignRun {
  std::string world;                ///< the file's stem
  std::vector<std::pair<std::string, std::string>> params;  ///< its sweep axes' values
  std::string name;                 ///< its folder in the campaign's
  std::uint64_t seed = 1;
  int exit_status = -1;
  bool success = false;
  /// The summary's: success, failed, no_path, unfinished ("" without one); "interrupted" for
  /// a run the campaign stopped.
  std::string end;
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

  /// Its value of the axis of that key; "" when it has none.
  std::string param(const std::string& axis_key) const;
};

/// A run of the product as it is before it flies: its world, seed, name and axes' values, no
/// result.
CampaignRun unflownRun(const PlannedRun& run);

/// The runs' summaries read back: a summary.json as `quad launch --summary` writes it.
/// Throws std::runtime_error naming the file when it is missing or not such a summary.
CampaignRun readRun(const std::filesystem::path& summary, const std::string& world, std::uint64_t seed,
                    int exit_status);

/// What would stop the campaign's runs at their start, found before any flies: each combination
/// of module axes' values checked by `quad launch --check` (the manifest, and every module's
/// parameters by its own schema), each world variant by the world loader. Empty: none.
std::vector<std::string> checkCampaign(const CampaignOptions& options);

/// Flies the product (planRuns), `jobs` at a time, writing each world variant into
/// <dir>/worlds/ first; `progress` hears each run as it ends. The runs come back in the
/// product's order, whatever order they ended in; after a stop, only those that ended, and
/// the interrupted ones marked so.
std::vector<CampaignRun> runCampaign(const CampaignOptions& options,
                                     const std::function<void(const CampaignRun&)>& progress = {});

/// Flies run `index` of the product alone, to its end (what a cluster's task does): in its
/// folder, on domain options.domain + index (wrapping before 233), its netns hosts on
/// 10.78.<index % 256>.0/24. Its result is also kept in its folder (storedResult), unless
/// options.stop said to stop while it flew: then it is "interrupted" and keeps none.
CampaignRun flyRun(const CampaignOptions& options, const PlannedRun& run, std::size_t index);

/// A run's result as its folder keeps it once it ended (its summary and the launcher's exit
/// status); nothing when it has none (never flown, or its flight cut short).
std::optional<CampaignRun> storedResult(const CampaignOptions& options, const PlannedRun& run);

/// A table for people: a row a run (a column per axis) and a last row of totals.
std::string table(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes = {});
/// The same as JSON: {"axes": {key: [values]}, "runs": [...], "succeeded": n, "runs_total": n}.
std::string toJson(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes = {});

}  // namespace quad::campaign
