// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/occupied_voxels.hpp"

namespace quad::display {

namespace {

// 21 bits an axis, offset to be non-negative: OctoMap's reach (2^15 voxels) fits.
constexpr std::int64_t kOffset = std::int64_t{1} << 20;
constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;

std::uint64_t pack(const geometry::VoxelIndex& i)
{
  const auto axis = [](int v) { return static_cast<std::uint64_t>(v + kOffset) & kMask; };
  return axis(i.x()) | (axis(i.y()) << 21) | (axis(i.z()) << 42);
}

geometry::VoxelIndex unpack(std::uint64_t key)
{
  const auto axis = [key](int shift) { return static_cast<int>(static_cast<std::int64_t>((key >> shift) & kMask) - kOffset); };
  return {axis(0), axis(21), axis(42)};
}

}  // namespace

void OccupiedVoxels::apply(const std::vector<mapping::VoxelChange>& changes)
{
  for (const auto& c : changes) {
    const std::uint64_t key = pack(c.index);
    if (c.state == mapping::VoxelState::kOccupied) {
      changed_ |= keys_.insert(key).second;
    } else {
      changed_ |= keys_.erase(key) > 0;
    }
  }
}

std::vector<geometry::Vector3> OccupiedVoxels::centres()
{
  changed_ = false;
  std::vector<geometry::Vector3> out;
  out.reserve(keys_.size());
  for (const auto key : keys_) {
    out.push_back(grid_.centre(unpack(key)));
  }
  return out;
}

}  // namespace quad::display
