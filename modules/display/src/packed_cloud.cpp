// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/packed_cloud.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace quad::display {

namespace {

void putFloat(std::uint8_t* out, double value)
{
  const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(value));
  for (int i = 0; i < 4; ++i) {
    out[i] = static_cast<std::uint8_t>(bits >> (8 * i));
  }
}

double getFloat(const std::uint8_t* in)
{
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) {
    bits |= static_cast<std::uint32_t>(in[i]) << (8 * i);
  }
  return static_cast<double>(std::bit_cast<float>(bits));
}

}  // namespace

PackedCloud packPoints(std::span<const Vector3> points, std::span<const Rgba> colours)
{
  if (!colours.empty() && colours.size() != points.size()) {
    throw std::invalid_argument("packPoints: " + std::to_string(colours.size()) + " colours for " +
                                std::to_string(points.size()) + " points");
  }
  using T = PackedField::Type;
  PackedCloud cloud;
  cloud.fields = {{"x", 0, T::kFloat32},   {"y", 4, T::kFloat32},   {"z", 8, T::kFloat32},
                  {"red", 12, T::kUint8},  {"green", 13, T::kUint8}, {"blue", 14, T::kUint8},
                  {"alpha", 15, T::kUint8}};
  cloud.data.resize(points.size() * PackedCloud::kStride);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = cloud.data.data() + i * PackedCloud::kStride;
    putFloat(p, points[i].x());
    putFloat(p + 4, points[i].y());
    putFloat(p + 8, points[i].z());
    const Rgba c = colours.empty() ? Rgba{} : colours[i];
    p[12] = c.r;
    p[13] = c.g;
    p[14] = c.b;
    p[15] = c.a;
  }
  return cloud;
}

Vector3 pointAt(const PackedCloud& cloud, std::size_t i)
{
  const std::uint8_t* p = cloud.data.data() + i * PackedCloud::kStride;
  return {getFloat(p), getFloat(p + 4), getFloat(p + 8)};
}

Rgba colourAt(const PackedCloud& cloud, std::size_t i)
{
  const std::uint8_t* p = cloud.data.data() + i * PackedCloud::kStride;
  return {p[12], p[13], p[14], p[15]};
}

Rgba heightColour(double z, double low, double high)
{
  // Three stops: dark blue, green, yellow; linear between them.
  constexpr std::array<std::array<double, 3>, 3> kStops{{{40, 60, 150}, {40, 170, 90}, {250, 220, 40}}};
  const double span = high - low;
  const double u = span > 0.0 && std::isfinite(z) ? std::clamp((z - low) / span, 0.0, 1.0) : 0.0;
  const double x = u * 2.0;
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), 1);
  const double f = x - static_cast<double>(k);
  const auto channel = [&](std::size_t c) {
    return static_cast<std::uint8_t>(std::lround(kStops[k][c] + (kStops[k + 1][c] - kStops[k][c]) * f));
  };
  return {channel(0), channel(1), channel(2), 255};
}

}  // namespace quad::display
