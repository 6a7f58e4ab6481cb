// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/packed_cloud.hpp"

#include <gtest/gtest.h>

#include <random>

namespace quad::display {
namespace {

TEST(PackedCloud, PointsAndColoursReadBackAsFloat32AndBytes)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  std::vector<Vector3> points;
  std::vector<Rgba> colours;
  for (int i = 0; i < 1000; ++i) {
    points.emplace_back(u(rng), u(rng), u(rng));
    colours.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(i / 4), 7, 200});
  }
  const PackedCloud cloud = packPoints(points, colours);
  ASSERT_EQ(cloud.size(), points.size());
  ASSERT_EQ(cloud.data.size(), points.size() * 16);
  for (std::size_t i = 0; i < points.size(); ++i) {
    // float32 keeps 24 bits: within 2^-23 of the value, relatively.
    EXPECT_LE((pointAt(cloud, i) - points[i]).norm(), 1e-5 * points[i].norm()) << i;
    EXPECT_EQ(colourAt(cloud, i).r, colours[i].r);
    EXPECT_EQ(colourAt(cloud, i).g, colours[i].g);
    EXPECT_EQ(colourAt(cloud, i).a, 200);
  }
}

TEST(PackedCloud, FieldsTileTheStrideAndAreLittleEndian)
{
  const std::vector<Vector3> one{{1.0, 0.0, 0.0}};
  const PackedCloud cloud = packPoints(one);
  std::uint32_t covered = 0;
  for (const auto& f : cloud.fields) {
    covered += f.type == PackedField::Type::kFloat32 ? 4U : 1U;
    EXPECT_LT(f.offset, PackedCloud::kStride) << f.name;
  }
  EXPECT_EQ(covered, PackedCloud::kStride);
  // 1.0f is 0x3f800000: the low byte first.
  EXPECT_EQ(cloud.data[0], 0x00);
  EXPECT_EQ(cloud.data[3], 0x3f);
  EXPECT_EQ(colourAt(cloud, 0).r, 255);  // white without colours
}

TEST(PackedCloud, ColoursOfAnotherLengthAreRefused)
{
  const std::vector<Vector3> two{{0, 0, 0}, {1, 1, 1}};
  const std::vector<Rgba> one{{}};
  EXPECT_THROW(packPoints(two, one), std::invalid_argument);
}

TEST(PackedCloud, HeightColoursRunFromTheLowStopToTheHighAndClamp)
{
  const Rgba low = heightColour(0.0, 0.0, 10.0);
  const Rgba high = heightColour(10.0, 0.0, 10.0);
  EXPECT_LT(low.r, high.r);
  EXPECT_LT(low.g, high.g);
  EXPECT_GT(low.b, high.b);
  EXPECT_EQ(heightColour(-5.0, 0.0, 10.0).b, low.b);
  EXPECT_EQ(heightColour(50.0, 0.0, 10.0).r, high.r);
  EXPECT_EQ(heightColour(3.0, 2.0, 2.0).b, low.b);  // an empty span is the low colour
}

}  // namespace
}  // namespace quad::display
