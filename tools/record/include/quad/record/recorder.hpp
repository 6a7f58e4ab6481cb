// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The recorder: subscribes to every quad topic (or those asked) as raw payloads, with each
/// topic's type discovered, and writes them to MCAP (omgidl schemas, cdr messages), chunked,
/// compressed, split by size or duration, with a per-topic loss audit; what its readers hold
/// when it is asked to stop is written too. `quad record` runs it, and `quad launch` runs
/// that for a run's recording.

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

#include "quad/topic/connection.hpp"

namespace quad::record {

struct RecordOptions {
  topic::ConnectionOptions connection;
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

/// Records until `stop` is set (by a signal handler), or the duration; the exit status.
int record(const RecordOptions& options, const std::atomic<int>& stop);

}  // namespace quad::record
