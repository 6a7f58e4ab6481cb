// SPDX-License-Identifier: BSD-3-Clause
#include "datagram_mutator.hpp"

#include <algorithm>
#include <string>

#include "rtps_builder.hpp"

namespace quad::fuzz {

DatagramMutator::DatagramMutator(std::uint64_t seed) : rng_(seed)
{
  using Builder = test::RtpsBuilder;
  constexpr std::uint8_t kGuidPrefix = 0xa0;
  const auto keep = [this](const Builder& b) {
    Template t{b.bytes(), {}};
    for (const auto& [offset, width] : b.fields()) {
      t.fields.push_back({offset, width});
    }
    templates_.push_back(std::move(t));
  };
  {  // SPDP: a discovery DATA with a parameter list (name, locators, a property list)
    Builder b(kGuidPrefix);
    b.begin(0x15, 0x04);
    b.dataHeader(0x000100c2, 1);
    b.u8(0x00);
    b.u8(0x03);  // PL_CDR_LE
    b.u16(0);
    b.parameter(0x0062, [&] { b.string("quad_fuzz"); });
    b.parameter(0x0032, [&] {
      b.u32(1);
      b.u32(7410);
      for (int i = 0; i < 12; ++i) {
        b.u8(0);
      }
      b.entity(0x7f000001);
    });
    b.parameter(0x0059, [&] {
      b.field(4);
      b.u32(2);
      b.string("fastdds.physical_data.host");
      b.string("quad");
      b.string("fastdds.physical_data.process");
      b.string("42");
    });
    b.parameter(0x002c, [&] {
      b.field(4);
      b.u32(3);
      b.u8(1);
      b.u8(2);
      b.u8(3);
      b.u8(0);
    });
    b.sentinel();
    b.end();
    keep(b);
  }
  {  // INFO_TS + a user DATA (a small CDR payload)
    Builder b(kGuidPrefix);
    b.begin(0x09, 0);
    b.u32(1);
    b.u32(2);
    b.end();
    b.begin(0x15, 0x04);
    b.dataHeader(0x00000102, 7);
    b.u8(0x00);
    b.u8(0x01);  // CDR_LE
    b.u16(0);
    for (int i = 0; i < 64; ++i) {
      b.u8(static_cast<std::uint8_t>(i));
    }
    b.end();
    keep(b);
  }
  {  // DATA_FRAG: fragment 2 of a 3000-byte sample in 1000-byte fragments
    Builder b(kGuidPrefix);
    b.begin(0x16, 0);
    b.dataHeader(0x00000102, 3, 28);
    b.field(4);
    b.u32(2);
    b.field(2);
    b.u16(1);
    b.field(2);
    b.u16(1000);
    b.field(4);
    b.u32(3000);
    for (int i = 0; i < 1000; ++i) {
      b.u8(static_cast<std::uint8_t>(i));
    }
    b.end();
    keep(b);
  }
  {  // HEARTBEAT + ACKNACK with a bitmap + GAP
    Builder b(kGuidPrefix);
    b.begin(0x07, 0);
    b.entity(0);
    b.entity(0x00000102);
    b.sn(1);
    b.sn(9);
    b.u32(1);
    b.end();
    b.begin(0x06, 0);
    b.entity(0x00000107);
    b.entity(0x00000102);
    b.sn(3);
    b.field(4);
    b.u32(40);
    b.u32(0xffffffff);
    b.u32(0xff);
    b.u32(1);
    b.end();
    b.begin(0x08, 0);
    b.entity(0x00000107);
    b.entity(0x00000102);
    b.sn(2);
    b.sn(4);
    b.field(4);
    b.u32(8);
    b.u32(0x3);
    b.end();
    keep(b);
  }
}

std::vector<std::uint8_t> DatagramMutator::next()
{
  const Template& t = templates_[static_cast<std::size_t>(rng_() % templates_.size())];
  std::vector<std::uint8_t> d = t.bytes;
  static const std::uint64_t kValues[] = {0,          1,          2,          3,          4,          7,
                                          8,          15,         16,         17,         27,         28,
                                          255,        256,        1000,       1400,       4095,       4096,
                                          32767,      32768,      65535,      65536,      0x7fffffff, 0x80000000,
                                          0xfffffffe, 0xffffffff, 0x100000000};
  const int changes = 1 + static_cast<int>(rng_() % 3);
  for (int c = 0; c < changes && !d.empty(); ++c) {
    switch (rng_() % 6) {
      case 0:
      case 1:
      case 2: {  // a field of the structure at a boundary value
        const Field& f = t.fields[static_cast<std::size_t>(rng_() % t.fields.size())];
        const std::uint64_t v = kValues[static_cast<std::size_t>(rng_() % std::size(kValues))] +
                                (rng_() % 4 == 0 ? static_cast<std::uint64_t>(rng_() % 9) - 4 : 0);
        for (std::size_t i = 0; i < f.width && f.offset + i < d.size(); ++i) {
          d[f.offset + i] = static_cast<std::uint8_t>(v >> (8 * i));
        }
        break;
      }
      case 3: {  // flags of the first submessage (endianness, inline QoS, data, key)
        if (d.size() > 21) {
          d[21] = static_cast<std::uint8_t>(rng_());
        }
        break;
      }
      case 4:  // cut short
        d.resize(static_cast<std::size_t>(rng_() % d.size()));
        break;
      default:  // a flipped byte behind the header
        if (d.size() > 20) {
          d[20 + static_cast<std::size_t>(rng_() % (d.size() - 20))] ^= static_cast<std::uint8_t>(1 + rng_() % 255);
        }
        break;
    }
  }
  return d;
}

}  // namespace quad::fuzz
