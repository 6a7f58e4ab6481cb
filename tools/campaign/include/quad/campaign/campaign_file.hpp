// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A campaign described in a file (`quad campaign --file FILE`, docs/campaign.md): its
/// manifest, worlds, seeds, axes and how it runs, read and checked whole before anything flies.
///
///   manifest: ../bringup/fast.yaml        # paths relative to the file
///   worlds: [../configs/worlds/benchmark_forest.yaml]
///   seeds: 1
///   jobs: 2
///   wall_timeout: 600
///   state: estimate                       # or truth; absent: the manifest's
///   layout: distributed                   # or composed; absent: the manifest's
///   record: true                          # false: no recording (nor run report) per run
///   axes:                                 # in this order, the last varying fastest
///     world:forest.density: [0.0204, 0.0278, 0.04]
///     world:forest.seed: 1..10
///     control:follower.max_speed: [3, 5, 7, 10]

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "quad/campaign/campaign.hpp"
#include "quad/campaign/sweep.hpp"

namespace quad::campaign {

struct CampaignFile {
  std::optional<std::filesystem::path> manifest;  ///< absolute
  std::vector<std::filesystem::path> worlds;      ///< absolute
  std::optional<int> seeds;
  std::optional<int> jobs;
  std::optional<double> wall_timeout_s;
  std::optional<std::string> state;
  std::optional<std::string> layout;
  std::optional<bool> record;
  std::vector<Axis> axes;
};

/// Reads and checks a campaign file; throws common::ConfigError listing every problem as
/// `file:key: value: reason`.
CampaignFile readCampaignFile(const std::filesystem::path& file);

/// The campaign file that gives `options` (absolute paths): manifest, worlds, seeds,
/// wall_timeout, state, layout, record and axes; what a cluster's tasks read.
std::string campaignFileText(const CampaignOptions& options);

}  // namespace quad::campaign
