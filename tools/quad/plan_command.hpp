// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad plan [--world W] [--config C | --manifest M]`: the known-map optimum of a world with
/// the planner's parameters (a config's, or those a manifest gives its planning module).

#include <optional>
#include <string>

namespace quad::tools {

struct PlanOptions {
  std::optional<std::string> world;  ///< replaces the planning config's world
  std::string config;                ///< the planning config (configs/planning.yaml)
  std::optional<std::string> manifest;  ///< instead: its planning module's config and set, its world
  bool no_land = false;              ///< the mission does not land at the goal
  std::optional<std::string> json;   ///< the result as JSON to this file
};

/// 0 with a path, 3 when none exists (as `quad launch`), 2 for bad input (named).
int plan(const PlanOptions& options);

}  // namespace quad::tools
