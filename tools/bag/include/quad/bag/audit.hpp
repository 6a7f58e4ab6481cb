// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Loss accounting from the Header.seq of each writer: every sample a writer published for a
/// vehicle has the number after its previous one for that vehicle (a plant simulating a fleet
/// numbers each vehicle's samples on their own), so gaps are missing samples, a number seen
/// twice is a duplicate, and a missing number that turns up later was reordered.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>

namespace quad::bag {

struct LossFigures {
  std::uint64_t received = 0;
  std::uint64_t missing = 0;     ///< numbers skipped and never seen
  std::uint64_t duplicated = 0;  ///< numbers seen more than once
  std::uint64_t reordered = 0;   ///< numbers that came after a later one
  LossFigures& operator+=(const LossFigures& o);
};

/// The metadata record of a recording that holds its loss figures, a value per topic.
inline constexpr std::string_view kLossMetadata = "quad.loss";

/// "received 120 missing 0 duplicated 0 reordered 0 writers 1": a recording's quad.loss
/// metadata value for one topic.
std::string toText(const LossFigures& f, std::size_t writers);
/// The figures of such a text; nothing when it is not one.
std::optional<LossFigures> parseLossFigures(std::string_view text);
/// The writers such a text counts; nothing when it is not one.
std::optional<std::size_t> parseLossWriters(std::string_view text);

class SequenceAudit {
public:
  /// One sample of `writer` (any id that tells writers apart) for `vehicle`
  /// (Header.vehicle_id) with its Header.seq.
  void add(std::uint64_t writer, std::uint32_t vehicle, std::uint64_t seq);
  LossFigures figures() const;
  /// The writers heard (a writer of several vehicles' samples counts once).
  std::size_t writers() const;

private:
  struct Writer {
    std::uint64_t last = 0;          // highest number seen
    std::set<std::uint64_t> gaps;    // numbers below `last` not seen yet
    LossFigures f;
  };
  std::map<std::pair<std::uint64_t, std::uint32_t>, Writer> writers_;  // by writer and vehicle
};

}  // namespace quad::bag
