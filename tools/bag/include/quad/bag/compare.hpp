// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Two recordings compared message by message, field by field through the IDL schema: what
/// `quad bag diff` and the determinism test use. Messages with quad's Header are paired by
/// their stamp (several of one stamp by their vehicle id, then in their recorded order), from where both recordings
/// hold the topic (a recorder subscribes once it sees a writer) to where the sooner of the
/// two clocks ended (that instant left out: a plant stopped there reports the run's end). A
/// sample sent again (the same stamp and content, a new number) counts
/// once; a message one recorder lost, as its loss figures count, is passed over, and so is one
/// only one recording holds within the last period of its topic (the channel's `rate_hz`)
/// before that end, where a lost sample has no later number to reveal it. Others are paired in
/// order.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quad/bag/mcap.hpp"

namespace quad::bag {

struct CompareOptions {
  /// Which topics take part (both recordings' topics are asked); null: every topic.
  std::function<bool(const std::string& topic)> selected;
  /// Members never compared, as "<scoped struct>.<member>" ("quad::msg::Header.publish_ns"):
  /// the ones that hold wall-clock or measured compute times.
  std::vector<std::string> ignored_fields;
  /// The topic whose newest stamp is where a recording ends (quad/sim/clock).
  std::string clock_topic;
};

/// Where two recordings first part.
struct Difference {
  std::string topic;
  std::uint64_t index = 0;   ///< 1-based position among the topic's compared messages
  std::int64_t stamp_ns = 0; ///< the first recording's Header.stamp_ns there (0 without one)
  /// The member's path ("waypoints_W[3].x"); "message" when only one recording holds this
  /// one (and its recorder counted no loss to explain it); "payload" for bytes that differ
  /// and are not quad's IDL; "topic" when only one recording has the topic.
  std::string field;
  std::string first, second;  ///< the two values (JSON text), or "present" / "absent"
};

struct Comparison {
  std::size_t topics = 0;            ///< topics compared
  std::uint64_t messages = 0;        ///< message pairs found equal
  /// Per topic, where it first differs; ordered by the first recording's log time there
  /// (a topic only one recording has comes first).
  std::vector<Difference> differences;
};

/// Compares `a` with `b`. A payload that does not decode as its schema's type is compared
/// byte for byte. Throws BagError when a channel names a schema neither the recording nor
/// quad's IDL defines.
Comparison compareRecordings(const McapContents& a, const McapContents& b, const CompareOptions& options);

}  // namespace quad::bag
