// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A structure-aware generator of hostile RTPS datagrams: well-formed templates of what quad's
/// participants exchange (discovery DATA with a parameter list, user DATA, DATA_FRAG,
/// HEARTBEAT, ACKNACK, GAP, INFO_TS), each with the offsets of its length, count, offset and
/// number fields, then broken where parsers trust them: those fields set to boundary values,
/// flags flipped, submessages cut, repeated or joined, bytes flipped. Seeded: the same seed
/// gives the same datagrams.

#include <cstdint>
#include <random>
#include <vector>

namespace quad::fuzz {

class DatagramMutator {
public:
  explicit DatagramMutator(std::uint64_t seed);

  /// The next hostile datagram.
  std::vector<std::uint8_t> next();

  /// The well-formed templates (each passes checkRtpsDatagram).
  std::size_t templates() const { return templates_.size(); }
  const std::vector<std::uint8_t>& templateBytes(std::size_t i) const { return templates_[i].bytes; }

private:
  struct Field {
    std::size_t offset;
    std::size_t width;  ///< 1, 2, 4 or 8 bytes
  };
  struct Template {
    std::vector<std::uint8_t> bytes;
    std::vector<Field> fields;  ///< where lengths, counts, offsets and numbers are
  };
  std::vector<Template> templates_;
  std::mt19937_64 rng_;
};

}  // namespace quad::fuzz
