// SPDX-License-Identifier: BSD-3-Clause
// The tree's two byte formats are OctoMap's own, byte for byte, for every tree a flight
// builds (empty, one scan, many scans with pruned free space), and they read back; a bounded
// map's, made from its voxels without the tree, are those of the tree OctoMap builds.
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

/// OctoMap's own image of `tree` (its two formats, its node count and memory use) is `image`.
void expectOctoMapsImage(const TreeImage& image, const octomap::OcTree& tree, int scan)
{
  ASSERT_EQ(image.binary, octomapBinary(tree)) << "after scan " << scan;
  ASSERT_EQ(image.data, octomapData(tree)) << "after scan " << scan;
  ASSERT_EQ(image.nodes, tree.size()) << "after scan " << scan;
  ASSERT_EQ(image.memory_bytes, tree.memoryUsage()) << "after scan " << scan;
}

TEST(TreeBytes, ABoundedMapsImageFromItsVoxelsIsOctoMapsOwnOfItsTree)
{
  // GIVEN a bounded map (its box not aligned to the octree's cubes) fed noisy scans: voxels
  // go up and down, siblings are pruned and expanded again
  Mapper mapper(test::boxedConfig());
  ASSERT_TRUE(mapper.tree().voxelBox().has_value());
  expectOctoMapsImage(mapper.image(true), mapper.tree(), -1);  // empty
  const std::vector<Scan> scans = test::noisyScans(36, 41);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    ASSERT_TRUE(mapper.integrate(scans[k]).accepted);
    // WHEN its image is made from the box's voxels (before the tree is settled), THEN it is
    // the image OctoMap writes of the tree, byte for byte
    const TreeImage image = mapper.image(true);
    expectOctoMapsImage(image, mapper.tree(), static_cast<int>(k));
    ASSERT_EQ(mapper.image(false).binary, image.binary);
    ASSERT_TRUE(mapper.image(false).data.empty());
  }
  // AND the tree it matched was pruned: leaves above the finest depth
  std::size_t pruned = 0;
  for (auto it = mapper.tree().begin_leafs(), end = mapper.tree().end_leafs(); it != end; ++it) {
    pruned += it.getDepth() < mapper.tree().getTreeDepth() ? 1U : 0U;
  }
  EXPECT_GT(pruned, 100U);
}

TEST(TreeBytes, AMapResumedWithVoxelsOutsideItsBoxImagesTheWholeTree)
{
  // GIVEN an unbounded map's node data, read into a bounded map whose box holds only part of it
  Mapper wide(MapperConfig{});
  const std::vector<Scan> scans = test::noisyScans(20, 43);
  for (std::size_t k = 0; k < 10; ++k) {
    ASSERT_TRUE(wide.integrate(scans[k]).accepted);
  }
  const std::vector<std::uint8_t> data = wide.image(true).data;
  std::istringstream in(std::string(data.begin(), data.end()));
  Mapper resumed(test::boxedConfig());
  ASSERT_TRUE(resumed.readTree(in));
  // THEN its voxels do not stand for its tree, and its images are the whole tree's still,
  // after more scans too
  EXPECT_FALSE(resumed.tree().voxelBox().has_value());
  expectOctoMapsImage(resumed.image(true), resumed.tree(), 9);
  for (std::size_t k = 10; k < scans.size(); ++k) {
    ASSERT_TRUE(resumed.integrate(scans[k]).accepted);
    expectOctoMapsImage(resumed.image(true), resumed.tree(), static_cast<int>(k));
  }
  EXPECT_GT(resumed.nodes(), wide.nodes() / 2);
}

}  // namespace
}  // namespace quad::mapping
