// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A lockstep recording cut into the rounds its clock drove: what `quad replay --inputs-of
/// MODULE --compare` feeds a module again. Each round is one sample of the sim clock and the
/// inputs stamped up to its time that came before it; the module's work for that time is
/// done before the next round starts, as the plant's lockstep waits for it.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "quad/bag/mcap.hpp"

namespace quad::bag {

struct Round {
  const Message* clock = nullptr;
  std::int64_t sim_ns = 0;
  bool state_sent = false;              ///< the plant sent the vehicle's state (or IMU sample) of this time
  std::vector<const Message*> inputs;   ///< to publish before the clock, in stamp order (then recorded order)
};

/// The rounds of `c`: one per sim time of `clock_topic` (a resent clock sample counts once),
/// in time order, with the messages of the topics `is_input` takes. An input goes to the
/// first round whose time is at or past its Header stamp; one stamped past the last clock
/// is left out, as is a sample sent again (the same channel, stamp and content but for its
/// number and publication time). Throws BagError when the clock does not decode as
/// quad::msg::SimClock.
std::vector<Round> lockstepRounds(const McapContents& c, const std::string& clock_topic,
                                  const std::function<bool(const std::string& topic)>& is_input);

/// A sample of an input the recorder lost: the rounds after `last_whole_ns` cannot be fed as
/// the run was.
struct LostInput {
  std::string topic;
  std::int64_t last_whole_ns = 0;  ///< the stamp of the topic's last message before the first gap
};

/// The earliest lost input of `c`: among the topics `is_input` takes whose loss figures
/// (quad.loss) count a missing sample, the first jump in Header.seq; with several writers on
/// such a topic the gap cannot be placed, and its first message counts as the last whole.
/// Nothing when the recorder lost no input.
std::optional<LostInput> firstLostInput(const McapContents& c, const std::function<bool(const std::string& topic)>& is_input);

}  // namespace quad::bag
