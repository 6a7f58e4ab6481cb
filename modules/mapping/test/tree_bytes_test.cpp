// SPDX-License-Identifier: BSD-3-Clause
// The tree's two byte formats are OctoMap's own, byte for byte, for every tree a flight
// builds (empty, one scan, many scans with pruned free space), and they read back.
#include "quad/mapping/tree_bytes.hpp"

#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>

#include "scans.hpp"

namespace quad::mapping {
namespace {

std::vector<std::uint8_t> octomapBinary(const octomap::OcTree& tree)
{
  std::ostringstream out;
  tree.writeBinaryConst(out);
  const std::string s = out.str();
  return {s.begin(), s.end()};
}

std::vector<std::uint8_t> octomapData(const octomap::OcTree& tree)
{
  std::ostringstream out;
  tree.writeData(out);
  const std::string s = out.str();
  return {s.begin(), s.end()};
}

TEST(TreeBytes, AreOctoMapsOwnAfterEveryScanOfAFlight)
{
  const world::World world = test::boxWorld();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mapper mapper(MapperConfig{});
  ASSERT_EQ(binaryTreeBytes(mapper.tree()), octomapBinary(mapper.tree()));
  ASSERT_TRUE(treeDataBytes(mapper.tree()).empty());
  ASSERT_EQ(treeImage(mapper.tree(), true).memory_bytes, mapper.tree().memoryUsage());
  for (int k = 0; k < 12; ++k) {
    const Vector3 p(-2.0 + 0.4 * k, 3.0 * u(rng), 1.0 + 0.5 * (u(rng) + 1.0));
    ASSERT_TRUE(mapper.integrate(test::scanFrom(world, p, 0.8 * u(rng), rng)).accepted);
    ASSERT_EQ(binaryTreeBytes(mapper.tree()), octomapBinary(mapper.tree())) << "after scan " << k;
    ASSERT_EQ(treeDataBytes(mapper.tree()), octomapData(mapper.tree())) << "after scan " << k;
    // AND one walk gives both, and the memory use OctoMap counts with a walk of its own
    const TreeImage image = treeImage(mapper.tree(), true);
    ASSERT_EQ(image.binary, octomapBinary(mapper.tree())) << "after scan " << k;
    ASSERT_EQ(image.data, octomapData(mapper.tree())) << "after scan " << k;
    ASSERT_EQ(image.memory_bytes, mapper.tree().memoryUsage()) << "after scan " << k;
    ASSERT_TRUE(treeImage(mapper.tree(), false).data.empty());
  }
  EXPECT_GT(mapper.nodes(), 10'000U);
}

TEST(TreeBytes, ReadBackByOctoMapToTheSameTree)
{
  const world::World world = test::boxWorld();
  std::mt19937_64 rng(9);
  Mapper mapper(MapperConfig{});
  for (int k = 0; k < 4; ++k) {
    ASSERT_TRUE(mapper.integrate(test::scanFrom(world, Vector3(-1.0 + k, 0.5 * k, 1.5), 0.1 * k, rng)).accepted);
  }
  const auto data = treeDataBytes(mapper.tree());
  std::istringstream in(std::string(data.begin(), data.end()));
  octomap::OcTree copy(mapper.resolution());
  copy.readData(in);
  ASSERT_TRUE(in);
  EXPECT_TRUE(copy == mapper.tree());

  const auto binary = binaryTreeBytes(mapper.tree());
  const auto voxels = classificationOf(binary, mapper.resolution());
  ASSERT_TRUE(voxels.has_value());
  test::expectSameClassification(*voxels, mapper.classification());
}

}  // namespace
}  // namespace quad::mapping
