// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad campaign WORLDS... [--seeds N]`: flies each world with each seed, prints a table,
/// writes JSON; exits non-zero when any run failed.

#include <optional>
#include <string>
#include <vector>

namespace quad::tools {

struct CampaignCommandOptions {
  std::vector<std::string> worlds;
  int seeds = 1;
  std::string manifest;                ///< bringup/demo.yaml
  std::optional<int> domain;           ///< default: $QUAD_DOMAIN_ID, else 0
  std::optional<std::string> json;     ///< default: <dir>/campaign.json
  std::optional<std::string> dir;      ///< default: log/campaign-<time>-<pid>
  double wall_timeout_s = 600.0;
  std::string state;                   ///< estimate | truth; empty: the manifest's
  std::string layout;                  ///< distributed | composed; empty: the manifest's
};

/// 0 when every run succeeded, 1 when any failed, 2 for bad input.
int campaign(const CampaignCommandOptions& options);

}  // namespace quad::tools
