// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad record`, `quad replay` and `quad bag ...`: topic traffic to MCAP files and back, and
/// what a file holds. One file per command: record_command.cpp, bag_command.cpp; quad replay
/// calls its engine (quad/replay/replay.hpp) straight from main.cpp.

#include <optional>
#include <string>
#include <vector>

#include "quad/record/recorder.hpp"
#include "quad/replay/replay.hpp"
#include "topic_commands.hpp"

namespace quad::tools {

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

struct BagEchoOptions {
  std::string file;
  std::vector<std::string> topics;  ///< names or globs; empty: every topic
  bool json = false;                ///< one JSON object a line, else YAML documents
  std::size_t max_elements = 0;     ///< longer sequences and arrays are cut (0: whole)
};

/// Prints a recording's messages on the topics asked for, in log-time order, decoded against
/// their IDL, each with its topic and log time; 1 when the file or a message cannot be read.
int bagEcho(const BagEchoOptions& options);

/// Rewrites a recording cut short (a killed recorder) whole, with index and summary.
int bagRecover(const std::string& file, std::string output);

}  // namespace quad::tools
