// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// campaign.html: a campaign on one page that any browser opens offline. The runs' table, each
/// linked to its own report; the success rate over each pair of the campaign's dimensions
/// (worlds, axes, seeds) as a heatmap; the distributions of flown length over the optimum,
/// closest approach and time to goal.

#include <filesystem>
#include <vector>

#include "quad/campaign/campaign.hpp"

namespace quad::campaign {

/// Writes campaign.html and its figures (campaign_*.svg) in `dir`, the campaign's folder, where
/// each run's report is `<run name>/run/report.html`. Returns the page's path; throws
/// std::runtime_error naming a file it cannot write.
std::filesystem::path writeCampaignReport(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes,
                                          const std::filesystem::path& dir);

}  // namespace quad::campaign
