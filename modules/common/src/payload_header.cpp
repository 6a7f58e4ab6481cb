// SPDX-License-Identifier: BSD-3-Clause
#include "quad/common/payload_header.hpp"

namespace quad::common {

std::optional<PayloadHeader> payloadHeader(std::span<const std::uint8_t> payload, bool vehicle_only)
{
  // Encapsulation: 2 bytes id (0x0000 CDR_BE, 0x0001 CDR_LE), 2 bytes options. Then the body:
  // vehicle_id u32 at 0, stamp_ns i64 at 8, publish_ns i64 at 16, seq u64 at 24.
  const std::size_t needed = 4 + (vehicle_only ? 4 : 32);
  if (payload.size() < needed || payload[0] != 0 || payload[1] > 1) {
    return std::nullopt;
  }
  const bool little = payload[1] == 1;
  const std::uint8_t* body = payload.data() + 4;
  auto read = [&](std::size_t at, std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t byte = body[at + (little ? i : n - 1 - i)];
      v |= byte << (8 * i);
    }
    return v;
  };
  PayloadHeader h;
  h.vehicle_id = static_cast<std::uint32_t>(read(0, 4));
  if (!vehicle_only) {
    h.stamp_ns = static_cast<std::int64_t>(read(8, 8));
    h.publish_ns = static_cast<std::int64_t>(read(16, 8));
    h.seq = read(24, 8);
  }
  return h;
}

}  // namespace quad::common
