#pragma once
/// @file
/// `quad launch MANIFEST`: starts a manifest's modules on their hosts, supervises them, and
/// flies its mission when it has one.

#include <cstdint>
#include <optional>
#include <string>

namespace quad::tools {

struct LaunchOptions {
  std::string manifest;
  std::optional<std::string> world;    ///< replaces the manifest's world
  bool realtime = false;               ///< mode realtime instead of the manifest's
  bool lockstep = false;               ///< mode lockstep instead of the manifest's
  std::optional<std::uint64_t> seed;   ///< ${seed} instead of the manifest's
  std::optional<int> domain;           ///< replaces the manifest's and the environment's
  std::optional<std::string> subnet;   ///< replaces the manifest's netns subnet
  std::optional<std::string> summary;  ///< JSON summary of the mission to this file
  std::optional<std::string> log_dir;  ///< the run's folder; default log/<name>-<time>
  std::optional<std::string> record;   ///< record every topic of the run to this MCAP file
  double wall_timeout_s = 0.0;         ///< stop and fail after this long; 0 = never
  bool quiet = false;                  ///< modules' output to their logs only
  bool check = false;                  ///< validate the manifest and exit
};

int launch(const LaunchOptions& options);

}  // namespace quad::tools
