// SPDX-License-Identifier: BSD-3-Clause
#include "quad/mapping/stuck_sensor.hpp"

#include <algorithm>

#include "quad/common/digest.hpp"

namespace quad::mapping {

bool StuckSensorCheck::repeats(std::span<const std::array<float, 3>> points, float max_range)
{
  std::uint64_t digest = common::kDigestStart;
  for (const auto& p : points) {
    digest = common::digest(std::as_bytes(std::span(p)), digest);
  }
  const bool hits = std::any_of(points.begin(), points.end(), [&](const std::array<float, 3>& p) {
    return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= max_range * max_range;
  });
  const bool same = last_ == digest;
  last_ = digest;
  return hits && same;
}

}  // namespace quad::mapping
