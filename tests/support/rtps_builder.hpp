// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Builds RTPS datagrams byte by byte for the checks, the fuzzers and the benchmark: a header,
/// then little-endian submessages whose lengths are filled in when they end. It records where
/// the fields a parser trusts are (lengths, counts, sequence numbers) for the fuzzers to break.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace quad::test {

class RtpsBuilder {
public:
  struct Field {
    std::size_t offset;
    std::size_t width;  ///< 1, 2, 4 or 8 bytes
  };

  /// The 20-byte header: RTPS 2.3, vendor eProsima, a GUID prefix first, first + 1, ...
  explicit RtpsBuilder(std::uint8_t guid_prefix_first = 1)
  {
    bytes_ = {'R', 'T', 'P', 'S', 2, 3, 0x01, 0x0f};
    for (int i = 0; i < 12; ++i) {
      bytes_.push_back(static_cast<std::uint8_t>(guid_prefix_first + i));
    }
  }

  /// A submessage header with the little-endian flag set; end() fills in its length.
  void begin(std::uint8_t id, std::uint8_t flags)
  {
    u8(id);
    u8(static_cast<std::uint8_t>(flags | 0x01));
    length_at_ = bytes_.size();
    field(2);
    u16(0);
  }
  void end() { patchLength(length_at_); }

  /// The header of a DATA or DATA_FRAG body: extra flags, octetsToInlineQos, reader, writer, SN.
  void dataHeader(std::uint32_t writer, std::int64_t sn, std::uint16_t to_inline_qos = 16, std::uint32_t reader = 0)
  {
    u16(0);
    field(2);
    u16(to_inline_qos);
    entity(reader);
    entity(writer);
    this->sn(sn);
  }

  void u8(std::uint8_t v) { bytes_.push_back(v); }
  void u16(std::uint16_t v)
  {
    u8(static_cast<std::uint8_t>(v));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v)
  {
    u16(static_cast<std::uint16_t>(v));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  /// Entity ids are octets, big-endian whatever the submessage's order.
  void entity(std::uint32_t v)
  {
    for (int shift = 24; shift >= 0; shift -= 8) {
      u8(static_cast<std::uint8_t>(v >> shift));
    }
  }
  void sn(std::int64_t v)
  {
    field(8);
    u32(static_cast<std::uint32_t>(v >> 32));
    u32(static_cast<std::uint32_t>(v));
  }
  /// A CDR string: length with the terminator, the characters, padding to 4 bytes.
  void string(const std::string& s)
  {
    field(4);
    u32(static_cast<std::uint32_t>(s.size() + 1));
    for (char c : s) {
      u8(static_cast<std::uint8_t>(c));
    }
    u8(0);
    while (bytes_.size() % 4 != 0) {
      u8(0);
    }
  }
  void fill(std::size_t count, std::uint8_t value) { bytes_.resize(bytes_.size() + count, value); }

  /// A parameter of a parameter list whose value `write` appends; its length is filled in.
  template <class Write>
  void parameter(std::uint16_t pid, Write write)
  {
    u16(pid);
    const std::size_t at = bytes_.size();
    field(2);
    u16(0);
    write();
    patchLength(at);
  }
  void sentinel()
  {
    u16(0x0001);
    u16(0);
  }

  /// Marks the next `width` bytes as a field worth breaking.
  void field(std::size_t width) { fields_.push_back({bytes_.size(), width}); }

  std::vector<std::uint8_t>& bytes() { return bytes_; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  const std::vector<Field>& fields() const { return fields_; }

private:
  /// The 16-bit length at `at`: the bytes from behind it to the end.
  void patchLength(std::size_t at)
  {
    const auto length = static_cast<std::uint16_t>(bytes_.size() - at - 2);
    bytes_[at] = static_cast<std::uint8_t>(length);
    bytes_[at + 1] = static_cast<std::uint8_t>(length >> 8);
  }

  std::vector<std::uint8_t> bytes_;
  std::vector<Field> fields_;
  std::size_t length_at_ = 0;
};

}  // namespace quad::test
