#pragma once
/// @file
/// `quad record`, `quad replay` and `quad bag ...`: topic traffic to MCAP files and back, and
/// what a file holds. One file per command: record_command.cpp, replay_command.cpp,
/// bag_command.cpp.

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
  std::string compression = "zstd";   ///< of chunks: "zstd" or "" (none)
  double split_size_mb = 0.0;         ///< start a new file past this size; 0: never
  double split_duration_s = 0.0;      ///< start a new file after this long; 0: never
};

struct ReplayOptions {
  ConnectionOptions connection;
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
int record(const RecordOptions& options);

/// Prints topics, types, counts, rates, time span and loss figures of a recording.
int bagInfo(const std::string& file);

/// Rewrites a recording cut short (a killed recorder) whole, with index and summary.
int bagRecover(const std::string& file, std::string output);

}  // namespace quad::tools
