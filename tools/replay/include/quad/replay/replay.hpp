// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Replaying recordings: republishing a recording's samples as they were, and a module run
/// alone in lockstep on its recorded inputs and compared with what it wrote in the run
/// (docs/recording.md). And how quad compares two runs' recordings, which `quad bag diff`
/// shares.

#include <functional>
#include <string>
#include <vector>

#include "quad/bag/compare.hpp"
#include "quad/topic/connection.hpp"

namespace quad::tools {

struct ReplayOptions {
  topic::ConnectionOptions connection;
  std::string file;
  std::vector<std::string> topics;   ///< names or globs; empty: every recorded quad topic
  std::vector<std::string> exclude;
  std::string inputs_of;             ///< a module: publish only what it does not write itself
  double rate = 1.0;                 ///< speed factor of the original timing
  double from_s = 0.0;               ///< seconds after the first message
  double to_s = 0.0;                 ///< 0: to the end
  bool loop = false;
  double wait_match_s = 3.0;         ///< wait this long for readers before the first sample
  /// With inputs_of: start that module alone, drive it in lockstep from the recording's clock
  /// with its recorded inputs, and compare its outputs with the recorded ones.
  bool compare = false;
  std::string run_dir;               ///< the run's folder (its run.json); empty: the recording's
  std::vector<std::string> sets;     ///< KEY=VALUE added to the module's command line
  double round_timeout_s = 20.0;     ///< wall time a round may wait for the module
  bool json = false;
};

/// Republishes a recording's samples as they were (payloads untouched) with their timing.
int replay(const ReplayOptions& options);

/// `quad replay RECORDING --inputs-of MODULE --compare`: 0 when the module's outputs are the
/// recorded ones, 1 at the first difference, 2 when it cannot run (docs/recording.md).
int replayCompare(const ReplayOptions& options);

/// How `quad bag diff` and `quad replay --compare` compare: the topics `selected` takes, up to
/// the sooner end of the sim clock, without the members that hold wall-clock or compute times.
bag::CompareOptions simPacedComparison(std::function<bool(const std::string& topic)> selected);

/// Prints a comparison: "identical: ..." or each topic's first difference; one JSON object
/// when `json` (docs/quad-command.md).
void printComparison(const bag::Comparison& c, bool json);

}  // namespace quad::tools
