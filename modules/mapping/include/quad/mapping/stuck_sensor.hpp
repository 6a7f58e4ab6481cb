// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A stuck depth camera: one that sends the same frame again. A live camera's range noise
/// never gives the same hits twice, so a frame whose hits repeat the frame before, bit for
/// bit, is a stuck sensor's; integrated from where the vehicle is now it would clear space
/// through what the camera saw from where it was (or, with the vehicle still, teach nothing).
/// Misses carry no noise: a view of the open sky repeats, and is no sign of one.

#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace quad::mapping {

class StuckSensorCheck {
public:
  /// Whether this frame's points (the sensor's frame [m]) hold a hit (a point within
  /// `max_range` of the sensor) and equal the frame before's, bit for bit. Remembers the
  /// frame for the next call, whatever the answer.
  bool repeats(std::span<const std::array<float, 3>> points, float max_range);

private:
  std::optional<std::uint64_t> last_;  // digest of the frame before's points
};

}  // namespace quad::mapping
