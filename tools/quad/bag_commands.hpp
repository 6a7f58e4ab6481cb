// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad record`, `quad replay` and `quad bag ...`: topic traffic to MCAP files and back, and
/// what a file holds. One file per command: record_command.cpp, replay_command.cpp,
/// bag_command.cpp.

#include <optional>
#include <string>
#include <vector>

#include "quad/record/recorder.hpp"
#include "topic_commands.hpp"

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
};

/// Republishes a recording's samples as they were (payloads untouched) with their timing.
int replay(const ReplayOptions& options);

/// Records until Ctrl-C, SIGTERM or the duration; returns the exit status.
int record(const record::RecordOptions& options);

/// Prints topics, types, counts, rates, time span and loss figures of a recording; as one JSON
/// object when `json` (docs/quad-command.md).
int bagInfo(const std::string& file, bool json);

struct BagDiffOptions {
  std::string first, second;
  std::vector<std::string> topics;   ///< names or globs; empty: every topic
  std::vector<std::string> exclude;
  bool all_topics = false;           ///< also the topics paced by wall time
  bool json = false;
};

/// Compares two recordings message by message; 0 when they agree, 1 when they differ, 2 when
/// one cannot be read (docs/recording.md).
int bagDiff(const BagDiffOptions& options);

/// Rewrites a recording cut short (a killed recorder) whole, with index and summary.
int bagRecover(const std::string& file, std::string output);

}  // namespace quad::tools
