// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The Header that leads every quad message (idl/quad/msg/Header.idl), read straight from a
/// serialized sample: what the recorder and raw readers need without knowing the type.

#include <cstdint>
#include <optional>
#include <span>

namespace quad::common {

/// The highest vehicle id: Header.vehicle_id is in [0, kMaxVehicleId] (QUAD_VEHICLE_ID,
/// manifests' and fleet files' ids); a received sample with another is refused.
inline constexpr std::uint32_t kMaxVehicleId = 1'000'000;

/// The most vehicles one domain flies: a fleet manifest or fleet file lists at most this
/// many, and every endpoint holds an instance per vehicle up to it (the DDS resource limit
/// max_instances, whose default of 10 would refuse an eleventh vehicle's samples).
inline constexpr std::int32_t kMaxFleetVehicles = 64;

struct PayloadHeader {
  std::uint32_t vehicle_id = 0;
  std::int64_t stamp_ns = 0;
  std::int64_t publish_ns = 0;
  std::uint64_t seq = 0;
};

/// Reads it from a plain CDR payload (4-byte encapsulation, big or little endian; members
/// aligned to their size from the end of the encapsulation). Nothing when the payload is
/// too short or not plain CDR. With `vehicle_only`, only vehicle_id is read (8 bytes suffice).
std::optional<PayloadHeader> payloadHeader(std::span<const std::uint8_t> payload, bool vehicle_only = false);

}  // namespace quad::common
