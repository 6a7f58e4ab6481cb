// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `quad topic ...`: inspect and drive the topics of a running stack.

#include <optional>
#include <string>

#include "quad/topic/connection.hpp"

namespace quad::tools {

struct TopicListOptions {
  topic::ConnectionOptions connection;
  double wait_s = 2.0;      ///< how long to listen to discovery
  bool contracts = false;   ///< print the declared contracts instead
  bool json = false;        ///< one JSON object (docs/quad-command.md) instead of a table
};

struct TopicEchoOptions {
  topic::ConnectionOptions connection;
  std::string topic;
  int count = 0;            ///< stop after this many samples; 0 = until Ctrl-C
  double timeout_s = 0.0;   ///< give up (exit 1) after this long without `count` samples; 0 = never
  bool json = false;        ///< one JSON object per line instead of YAML
  std::size_t max_elements = 16;
};

struct TopicPubOptions {
  topic::ConnectionOptions connection;
  std::string topic;
  std::string values;       ///< YAML, e.g. "{kind: COMMAND_HOLD}"
  int count = 1;
  double rate_hz = 1.0;
  double wait_match_s = 5.0;
};

struct TopicInfoOptions {
  topic::ConnectionOptions connection;
  std::string topic;
  double wait_s = 2.0;      ///< how long to listen to discovery
  bool json = false;        ///< one JSON object (docs/quad-command.md) instead of text
};

struct TopicHzOptions {
  topic::ConnectionOptions connection;
  std::string topic;
  double duration_s = 0.0;  ///< 0: until Ctrl-C
  double window_s = 1.0;    ///< a line per window
  bool json = false;        ///< one JSON object per line (docs/quad-command.md) instead of text
};

int topicList(const TopicListOptions& options);
/// The contract of a topic, and the writers and readers seen, with their participants and hosts.
int topicInfo(const TopicInfoOptions& options);
/// The measured rate of a topic against its contract's.
int topicHz(const TopicHzOptions& options);
int topicEcho(const TopicEchoOptions& options);
int topicPub(const TopicPubOptions& options);

}  // namespace quad::tools
