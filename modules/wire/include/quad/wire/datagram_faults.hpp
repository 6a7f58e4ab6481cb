// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Faults on the datagrams a participant receives: loss, delay, duplication, reordering and
/// corruption, each drawn at random per datagram from a seeded generator. The decisions live
/// here, without Fast DDS; the transport layer that applies them to UDP (fault_transport.cpp)
/// asks `DatagramFaults::fate` once per datagram.

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace quad::wire {

enum class DatagramFaultKind { kLoss, kDelay, kDuplicate, kReorder, kCorrupt };

/// "loss", "delay", ...
std::string toString(DatagramFaultKind kind);

/// One fault on received datagrams.
struct DatagramFault {
  std::uint32_t id = 0;        ///< names it for clearing; 0 is invalid
  DatagramFaultKind kind = DatagramFaultKind::kLoss;
  /// Probability in [0, 1] per datagram; for kDelay the delay in seconds, in [0, 10].
  double magnitude = 0.0;
  /// The sending participant's name: only its datagrams are affected; empty for every sender.
  std::string from;
  std::uint64_t seed = 1;

  /// Why the fault cannot be applied, empty when it can.
  std::string invalidReason() const;
  /// "loss 0.2 of datagrams from mapping (seed 7)"
  std::string describe() const;
};

/// What happens to one received datagram.
struct DatagramFate {
  bool drop = false;
  int copies = 1;                      ///< 2 when duplicated
  std::int64_t delay_ns = 0;           ///< delivered this much later
  std::optional<std::size_t> corrupt;  ///< the byte whose bit `corrupt_bit` is flipped
  int corrupt_bit = 0;

  bool untouched() const { return !drop && copies == 1 && delay_ns == 0 && !corrupt; }
};

/// The faults active on one participant's received datagrams, by id. Thread-safe: Fast DDS's
/// receive threads ask for fates while the node applies and clears faults.
class DatagramFaults {
public:
  /// RTPS: "RTPS", protocol version (2), vendor id (2), then the sender's GUID prefix (12).
  static constexpr std::size_t kRtpsHeaderSize = 20;
  /// A reordered datagram is held this long, so that the ones after it overtake it.
  static constexpr std::int64_t kReorderHoldNs = 20'000'000;
  using GuidPrefix = std::array<std::uint8_t, 12>;

  /// Adds the fault; false (and nothing changes) if its id is in use or it is invalid.
  bool apply(const DatagramFault& fault);
  /// What one fault did while it was active.
  struct Tally {
    std::uint64_t affected = 0;  ///< datagrams from its sender(s)
    std::uint64_t acted = 0;     ///< of them, dropped, delayed, duplicated, held back or corrupted
  };
  /// Ends the fault and says what it did; nothing if no fault has that id.
  std::optional<Tally> clear(std::uint32_t id);
  /// The active faults' tallies, by id.
  std::map<std::uint32_t, Tally> tallies() const;
  /// The id was applied at some time (it may have been cleared since).
  bool knows(std::uint32_t id) const;
  /// No fault at all: the layer passes every datagram through untouched.
  bool idle() const;

  /// Names the participant that sends with `prefix` (learnt from discovery).
  void learnSender(const GuidPrefix& prefix, const std::string& name);

  /// Decides what happens to a received datagram. A datagram too short for an RTPS header
  /// has no known sender and meets only the faults on every sender.
  DatagramFate fate(const std::uint8_t* datagram, std::size_t size);

  /// Datagrams seen and what was done to them, for logs and tests.
  struct Counts {
    std::uint64_t seen = 0, dropped = 0, delayed = 0, duplicated = 0, reordered = 0, corrupted = 0;
  };
  Counts counts() const;

private:
  struct Active {
    DatagramFault fault;
    std::mt19937_64 rng;
    Tally tally;
  };
  bool affects(const Active& a, const std::string* sender) const;

  mutable std::mutex mutex_;
  std::map<std::uint32_t, Active> active_;
  std::set<std::uint32_t> known_;
  std::map<GuidPrefix, std::string> senders_;
  Counts counts_;
};

}  // namespace quad::wire
