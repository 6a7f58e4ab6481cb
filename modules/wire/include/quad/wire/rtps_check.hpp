// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Structure checks of a received RTPS datagram (the OMG DDSI-RTPS 2.x wire format), made
/// before Fast DDS parses it: Fast DDS 2.9 trusts lengths, counts and fragment numbers it
/// reads, and a single malformed datagram can end its process. The checks need no Fast DDS;
/// the validating transport (validating_transport.hpp) applies them to every datagram.
///
/// What is checked:
/// - the header: at least 20 bytes, "RTPS", protocol major version 2;
/// - each submessage: its header and body within the datagram; a body long enough for the
///   fields of its kind; sequence and fragment number sets with at most 256 bits and their
///   bitmaps present; sequence numbers and fragment numbers where the specification requires
///   them to be positive; DATA_FRAG's fragment size, count, start and sample size consistent
///   with each other and with the bytes present, and the sample within kMaxSampleBytes;
/// - parameter lists (inline QoS, and discovery payloads encapsulated as PL_CDR): every
///   parameter within the list, lengths multiples of 4, a sentinel at the end; the values of
///   the parameters Fast DDS decodes into strings, sequences, locators, GUIDs, properties and
///   security tokens: every string and sequence length within its parameter;
/// - the key of a keyed user sample: a key hash in its inline QoS must be the key its payload
///   holds, the payload's first member Header.vehicle_id (every quad keyed type leads with
///   Header, and the vehicle id is its whole key). Fast DDS files a sample under the instance
///   its key names, and a single damaged bit there would invent one.
///
/// Encrypted content (SEC_* and SRTPS_* submessages) is checked for lengths only; fragments
/// are checked one by one, not reassembled (a discovery payload split into fragments has its
/// parameter list checked by Fast DDS alone).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace quad::wire {

/// The largest sample a DATA_FRAG may announce: Fast DDS reserves that much memory for its
/// reassembly when the first fragment arrives. Four times the largest message quad sends
/// (a 4 MiB map snapshot).
inline constexpr std::uint32_t kMaxSampleBytes = 16u * 1024u * 1024u;

/// What is wrong with a datagram: where and what.
struct RtpsDefect {
  std::size_t offset = 0;  ///< of the submessage, parameter or field at fault
  std::string what;        ///< "DATA_FRAG: fragment 3 of 2 ..."
};

/// A count a receiver only lets grow: HEARTBEAT and HEARTBEAT_FRAG carry one per writer,
/// ACKNACK and NACK_FRAG one per reader and writer; a submessage whose count is not above the
/// highest taken from its sender is ignored.
struct RtpsCount {
  std::uint8_t kind = 0;                 ///< the submessage id
  bool per_writer = false;               ///< a writer's count across its readers (HEARTBEAT, HEARTBEAT_FRAG)
  std::array<std::uint8_t, 12> prefix{};  ///< the sender's GUID prefix (header, or INFO_SRC)
  std::uint32_t reader_id = 0;           ///< entity ids as on the wire (big-endian octets)
  std::uint32_t writer_id = 0;
  std::uint32_t count = 0;
  std::size_t offset = 0;                ///< of the submessage
  std::size_t count_offset = 0;          ///< of the count field
  bool little_endian = false;            ///< the count's byte order
};

/// The highest sequence number of a writer that a submessage states: DATA and DATA_FRAG
/// their sample's, HEARTBEAT and HEARTBEAT_FRAG the last the writer has, GAP the last it
/// declares irrelevant (an upper bound: its list's base + bit count - 1).
struct RtpsSequence {
  std::uint8_t kind = 0;                 ///< the submessage id
  std::array<std::uint8_t, 12> prefix{};  ///< the sender's GUID prefix (header, or INFO_SRC)
  std::uint32_t writer_id = 0;           ///< as on the wire (big-endian octets)
  std::int64_t last = 0;
  std::size_t offset = 0;  ///< of the submessage
};

/// Nothing when `data` is a well-formed RTPS message; else its first defect. With `counts`
/// (`sequences`), a well-formed message's counts (sequence numbers) are appended to it on
/// the same pass.
std::optional<RtpsDefect> checkRtpsDatagram(const std::uint8_t* data, std::size_t size,
                                            std::vector<RtpsCount>* counts = nullptr,
                                            std::vector<RtpsSequence>* sequences = nullptr);

}  // namespace quad::wire
