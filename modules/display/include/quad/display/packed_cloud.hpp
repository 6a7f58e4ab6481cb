// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Points packed for a viewer's point cloud (Foxglove's PointCloud): each point x, y, z as
/// float32, then red, green, blue, alpha as uint8, little endian: 16 bytes a point.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::display {

using geometry::Vector3;

struct Rgba {
  std::uint8_t r = 255;
  std::uint8_t g = 255;
  std::uint8_t b = 255;
  std::uint8_t a = 255;
};

/// One field of each point.
struct PackedField {
  enum class Type { kUint8, kFloat32 };
  std::string name;
  std::uint32_t offset = 0;  ///< [bytes] from the point's start
  Type type = Type::kFloat32;
};

struct PackedCloud {
  static constexpr std::uint32_t kStride = 16;  ///< [bytes] a point
  std::vector<PackedField> fields;
  std::vector<std::uint8_t> data;
  std::size_t size() const { return data.size() / kStride; }
};

/// Packs points with their colours (`colours` as long as `points`, or empty for white).
/// Throws std::invalid_argument when the lengths differ.
PackedCloud packPoints(std::span<const Vector3> points, std::span<const Rgba> colours = {});

/// A point of a packed cloud, read back.
Vector3 pointAt(const PackedCloud& cloud, std::size_t i);
Rgba colourAt(const PackedCloud& cloud, std::size_t i);

/// A colour for a height between `low` and `high` (clamped): dark blue low, through green,
/// to yellow high, so that a map's shape reads in a cloud seen from above.
Rgba heightColour(double z, double low, double high);

}  // namespace quad::display
