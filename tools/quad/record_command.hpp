#pragma once
/// @file
/// `quad record` and `quad bag info`: topic traffic to MCAP files, and what a file holds.

#include <optional>
#include <string>
#include <vector>

#include "topic_commands.hpp"

namespace quad::tools {

struct RecordOptions {
  ConnectionOptions connection;
  std::string output;                 ///< empty: quad-<time>.mcap
  std::vector<std::string> topics;    ///< names or globs; empty: every quad topic
  std::vector<std::string> exclude;   ///< globs
  double duration_s = 0.0;            ///< 0: until Ctrl-C
  bool quiet = false;                 ///< no progress line
  std::size_t chunk_size = 1 << 20;   ///< bytes of messages per chunk
};

/// Records until Ctrl-C, SIGTERM or the duration; returns the exit status.
int record(const RecordOptions& options);

/// Prints topics, types, counts, rates, time span and loss figures of a recording.
int bagInfo(const std::string& file);

/// Rewrites a recording cut short (a killed recorder) whole, with index and summary.
int bagRecover(const std::string& file, std::string output);

}  // namespace quad::tools
