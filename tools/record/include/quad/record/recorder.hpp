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
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "quad/dds/participant.hpp"
#include "quad/dds/waker.hpp"
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

/// The recorder on a participant it is given: a participant of its own (quad record), or the
/// one a container's modules share (the recorder hosted beside them, whose readers then take
/// their samples on the writer's thread, with no socket between; docs/recording.md).
class Recorder {
public:
  /// Subscribes to every topic `options` selects and opens the first file; throws
  /// bag::BagError when it cannot. `waker` is notified as samples arrive (nullptr: never).
  Recorder(dds::Participant& participant, const RecordOptions& options, dds::Waker* waker);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Takes and writes every sample the readers hold; every 200 ms names the writers the
  /// recording leaves out; releases a lockstep run's start once the plant's writers matched;
  /// draws the progress line once a second. Throws bag::BagError when a file cannot be
  /// written, once: after it, nothing is taken.
  void poll();
  /// [ns, steady clock] When poll() next has something to do if no sample comes.
  std::int64_t nextDueNs() const;
  /// Writes what the readers still hold and closes the recording with its loss figures, once;
  /// false when it could not (said on stderr).
  bool finish();

private:
  struct State;
  std::unique_ptr<State> s_;
};

/// Records until `stop` is set (by a signal handler), or the duration; the exit status.
int record(const RecordOptions& options, const std::atomic<int>& stop);

}  // namespace quad::record
