// SPDX-License-Identifier: BSD-3-Clause
// The mapper on scans ray-cast by the plant's depth camera, fixed seeds.
#include "quad/mapping/mapper.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <random>
#include <sstream>

#include "scans.hpp"

namespace quad::mapping {
namespace {

using test::boxWorld;
using test::boxedConfig;
using test::noisyScans;
using test::scanFrom;

VoxelIndex voxelAt(const Mapper& m, const Vector3& p) { return geometry::VoxelGrid(m.resolution()).toIndex(p); }

TEST(Mapper, AKnownBoxIsOccupiedOnItsFaceFreeInFrontUnknownBehind)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(1);
  Mapper mapper(MapperConfig{});
  const auto result = mapper.integrate(scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  ASSERT_TRUE(result.accepted) << result.rejection;
  EXPECT_GT(result.changes.size(), 100U);
  // The face x = 5 seen head-on: its voxels (x in [5.0, 5.2)) are occupied.
  for (const double y : {-0.7, -0.3, 0.1, 0.5}) {
    for (const double z : {0.5, 1.1, 1.7, 2.3}) {
      EXPECT_EQ(mapper.classify(voxelAt(mapper, Vector3(5.05, y, z))), VoxelState::kOccupied) << y << " " << z;
    }
  }
  // In front of it: free.
  for (const double x : {1.0, 2.5, 4.0, 4.7}) {
    EXPECT_EQ(mapper.classify(voxelAt(mapper, Vector3(x, 0.1, 1.5))), VoxelState::kFree) << x;
  }
  // Inside and behind it: never seen.
  for (const double x : {5.9, 6.5, 7.5, 9.0}) {
    EXPECT_EQ(mapper.classify(voxelAt(mapper, Vector3(x, 0.1, 1.5))), VoxelState::kUnknown) << x;
  }
}

TEST(Mapper, ChangeSetsReplayedInOrderReproduceTheMapExactly)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mapper mapper(MapperConfig{});
  VoxelMap replica(mapper.resolution());
  for (int k = 0; k < 25; ++k) {
    const Vector3 p(-2.0 + 0.3 * k, 4.0 * u(rng), 1.0 + 0.5 * (u(rng) + 1.0));
    const auto result = mapper.integrate(scanFrom(world, p, 0.6 * u(rng), rng));
    ASSERT_TRUE(result.accepted);
    replica.apply(result.changes);
    ASSERT_EQ(replica.contents().size(), mapper.classification().size()) << "after scan " << k;
  }
  test::expectSameClassification(mapper.classification(), replica.contents());
}

/// What changed between two classifications (both sorted by index): each voxel whose state
/// differs, with its state after (unknown when it left the map).
std::vector<VoxelChange> differenceOf(const std::vector<VoxelChange>& before, const std::vector<VoxelChange>& after)
{
  std::vector<VoxelChange> out;
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < after.size()) {
    if (j == after.size() || (i < before.size() && indexLess(before[i].index, after[j].index))) {
      out.push_back({before[i++].index, VoxelState::kUnknown});
    } else if (i == before.size() || indexLess(after[j].index, before[i].index)) {
      out.push_back(after[j++]);
    } else {
      if (before[i].state != after[j].state) {
        out.push_back(after[j]);
      }
      ++i;
      ++j;
    }
  }
  return out;
}

TEST(Mapper, BuildsTheTreeOctomapBuildsAndReportsExactlyTheReclassifiedVoxels)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.08);
  // A threshold above the hit probability too: a voxel's first hit then leaves it free.
  for (const double threshold : {0.5, 0.8}) {
    MapperConfig config;
    config.max_range = 8.0;  // many rays end beyond it and only clear space
    config.occupancy_threshold = threshold;
    Mapper mapper(config);
    octomap::OcTree bare(config.resolution);
    bare.setProbHit(config.prob_hit);
    bare.setProbMiss(config.prob_miss);
    bare.setClampingThresMin(config.clamp_min);
    bare.setClampingThresMax(config.clamp_max);
    bare.setOccupancyThres(config.occupancy_threshold);
    for (int k = 0; k < 30; ++k) {
      Scan scan = scanFrom(world, Vector3(-2.0 + 0.1 * k, 1.5 * u(rng), 1.5 + 0.5 * u(rng)), 0.3 * u(rng), rng);
      octomap::Pointcloud cloud;
      for (Vector3& p : scan.points_W) {
        p += Vector3(noise(rng), noise(rng), noise(rng));
        cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
      }
      const auto before = mapper.classification();
      const IntegrationResult result = mapper.integrate(scan);
      ASSERT_TRUE(result.accepted);
      bare.insertPointCloud(cloud, octomap::point3d(static_cast<float>(scan.origin_W.x()), static_cast<float>(scan.origin_W.y()),
                                                    static_cast<float>(scan.origin_W.z())),
                            std::min(scan.max_range, config.max_range));
      // The same tree, node for node and log-odds for log-odds (OctoMap's full .ot format).
      std::ostringstream ours, theirs;
      mapper.tree().write(ours);
      bare.write(theirs);
      ASSERT_EQ(ours.str(), theirs.str()) << "threshold " << threshold << ", after scan " << k;
      test::expectSameClassification(differenceOf(before, mapper.classification()), result.changes);
    }
    EXPECT_LT(mapper.nodes(), 8 * mapper.classification().size()) << "the tree was pruned";
  }
}

TEST(Mapper, ALateJoinerCatchesUpFromASnapshotAndLaterChanges)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(11);
  Mapper mapper(MapperConfig{});
  VoxelMap from_start(mapper.resolution());
  VoxelMap late(mapper.resolution());
  for (int k = 0; k < 20; ++k) {
    const auto result = mapper.integrate(scanFrom(world, Vector3(-1.0 + 0.4 * k, 0.2 * k - 2.0, 1.5), 0.1 * k, rng));
    from_start.apply(result.changes);
    if (k == 9) {
      ASSERT_TRUE(late.applySnapshot(mapper.snapshot()));
    } else if (k > 9) {
      late.apply(result.changes);
    }
  }
  test::expectSameClassification(from_start.contents(), late.contents());
}

TEST(Mapper, SavedBtFilesLoadInOctomapWithTheSameClassification)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(3);
  Mapper mapper(MapperConfig{});
  mapper.integrate(scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  const auto file = std::filesystem::temp_directory_path() / "quad_mapper_test.bt";
  ASSERT_TRUE(mapper.save(file));
  octomap::OcTree loaded(file.string());
  EXPECT_DOUBLE_EQ(loaded.getResolution(), 0.2);
  const auto expected = mapper.classification();
  const auto actual = classificationOf(loaded);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(actual[i].state, expected[i].state);
  }
  std::filesystem::remove(file);
}

TEST(Mapper, BadCloudsAreRefusedWholeAndChangeNothing)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(5);
  MapperConfig config;
  config.max_points = 5000;
  Mapper mapper(config);
  mapper.integrate(scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  const auto before = mapper.classification();
  Scan bad = scanFrom(world, Vector3(1, 0, 1.5), 0.0, rng);
  bad.points_W[100].y() = std::nan("");
  EXPECT_EQ(mapper.integrate(bad).rejection, "point 100 is not finite");
  bad = scanFrom(world, Vector3(1, 0, 1.5), 0.0, rng);
  bad.origin_W.x() = INFINITY;
  EXPECT_EQ(mapper.integrate(bad).rejection, "sensor origin or range is not finite");
  bad = scanFrom(world, Vector3(1, 0, 1.5), 0.0, rng);
  bad.points_W.resize(6000, Vector3(3, 0, 1));
  EXPECT_EQ(mapper.integrate(bad).rejection, "6000 points exceed map.max_points (5000)");
  const auto after = mapper.classification();
  EXPECT_EQ(after.size(), before.size());
}

TEST(Mapper, ContradictoryConfigIsRefusedNamingTheKey)
{
  const common::ParamSchema& schema = mapperTable().schema();
  const auto problems = [&](const std::string& yaml) {
    try {
      mapperConfigFrom(common::parseParams(yaml, "mapping.yaml", schema));
    } catch (const common::ConfigError& e) {
      return e.problems();
    }
    return std::vector<std::string>{"accepted"};
  };
  EXPECT_EQ(problems("map: {prob_hit: 0.4}"),
            std::vector<std::string>{"mapping.yaml:map.prob_hit: 0.4: must exceed 0.5, or hits would clear space"});
  EXPECT_EQ(problems("map: {clamp_min: 0.6}"),
            std::vector<std::string>{"mapping.yaml:map.clamp_min: 0.6: must be below map.occupancy_threshold (0.5)"});
  EXPECT_EQ(problems("map: {resolution: 0}"),
            std::vector<std::string>{"mapping.yaml:map.resolution: 0: out of range [0.01, 10] m"});
  EXPECT_EQ(problems("map: {max_range: .nan}"),
            std::vector<std::string>{"mapping.yaml:map.max_range: .nan: not a finite number"});
}

TEST(Mapper, HeightLimitsAndMinimumRangeDropPoints)
{
  const world::World world = boxWorld();
  std::mt19937_64 rng(5);
  MapperConfig config;
  config.max_z = 1.0;
  config.min_z = 0.1;
  Mapper mapper(config);
  const auto result = mapper.integrate(scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  EXPECT_LT(result.points, 64U * 48U);
  EXPECT_EQ(mapper.classify(voxelAt(mapper, Vector3(5.05, 0.1, 2.3))), VoxelState::kUnknown);  // above max_z
  EXPECT_EQ(mapper.classify(voxelAt(mapper, Vector3(5.05, 0.1, 0.5))), VoxelState::kOccupied);
}


TEST(Mapper, ABoxedMapIsTheUnboundedMapCutToItsBox)
{
  // GIVEN two mappers fed the same scans, one limited to x -1 ... 5.6, z 0 ... 2.4
  const world::World world = boxWorld();
  MapperConfig boxed_config;
  boxed_config.box = std::make_pair(Vector3(-1.0, -20.0, 0.0), Vector3(5.6, 20.0, 2.4));
  Mapper free_mapper(MapperConfig{});
  Mapper boxed(boxed_config);
  std::mt19937_64 rng(3);
  std::size_t free_changes = 0, boxed_changes = 0;
  for (int k = 0; k < 6; ++k) {
    const Vector3 p(-0.5 + 0.5 * k, 0.3 * k - 1.0, 1.5);
    std::mt19937_64 copy = rng;
    free_changes += free_mapper.integrate(scanFrom(world, p, 0.1 * k, rng)).changes.size();
    boxed_changes += boxed.integrate(scanFrom(world, p, 0.1 * k, copy)).changes.size();
  }
  // THEN the boxed map holds exactly the unbounded map's voxels whose index lies in the box's
  const geometry::VoxelGrid grid(boxed.resolution());
  const VoxelIndex lo = grid.toIndex(boxed_config.box->first);
  const VoxelIndex hi = grid.toIndex(boxed_config.box->second);
  std::vector<VoxelChange> cut;
  for (const auto& c : free_mapper.classification()) {
    if ((c.index.array() >= lo.array()).all() && (c.index.array() <= hi.array()).all()) {
      cut.push_back(c);
    }
  }
  test::expectSameClassification(cut, boxed.classification());
  // and the box saved most of the work: rays past it touched nothing
  EXPECT_LT(boxed_changes * 2, free_changes);
  EXPECT_LT(boxed.nodes() * 2, free_mapper.nodes());
}

TEST(Mapper, ABoxedMapsVoxelsHoldTheUnboundedMapsLogOddsWhateverUpdatesItsBoundsSkipped)
{
  // GIVEN two mappers fed the same noisy scans of a box approached slowly (so that most
  // voxels reach a clamping bound, and noise moves hits on and off the box's face), one
  // limited to a box around it, whose voxels' bounds it keeps
  const world::World world = boxWorld();
  MapperConfig boxed_config;
  boxed_config.max_range = 8.0;
  boxed_config.box = std::make_pair(Vector3(-1.0, -3.0, 0.0), Vector3(8.0, 3.0, 3.0));
  MapperConfig free_config;
  free_config.max_range = 8.0;
  Mapper free_mapper(free_config);
  Mapper boxed(boxed_config);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.08);
  octomap::OcTreeKey lo, hi;
  ASSERT_TRUE(boxed.tree().coordToKeyChecked(octomap::point3d(-0.99F, -2.99F, 0.01F), lo));
  ASSERT_TRUE(boxed.tree().coordToKeyChecked(octomap::point3d(7.99F, 2.99F, 2.99F), hi));
  for (int k = 0; k < 40; ++k) {
    Scan scan = scanFrom(world, Vector3(-0.5 + 0.05 * k, 0.5 * u(rng), 1.5 + 0.3 * u(rng)), 0.2 * u(rng), rng);
    for (Vector3& p : scan.points_W) {
      p += Vector3(noise(rng), noise(rng), noise(rng));
    }
    const IntegrationResult free_result = free_mapper.integrate(scan);
    const IntegrationResult boxed_result = boxed.integrate(scan);
    ASSERT_TRUE(free_result.accepted && boxed_result.accepted);
    // THEN every scan reclassifies the same voxels within the box
    const geometry::VoxelGrid grid(boxed.resolution());
    const VoxelIndex box_lo = grid.toIndex(boxed_config.box->first);
    const VoxelIndex box_hi = grid.toIndex(boxed_config.box->second);
    std::vector<VoxelChange> cut;
    for (const auto& c : free_result.changes) {
      if ((c.index.array() >= box_lo.array()).all() && (c.index.array() <= box_hi.array()).all()) {
        cut.push_back(c);
      }
    }
    test::expectSameClassification(cut, boxed_result.changes);
    if (k % 8 != 7) {
      continue;
    }
    // AND each voxel of the box holds the unbounded map's log-odds, or is unknown in both
    const MapTree& tree = boxed.tree();  // brought up to date with the scans
    for (auto x = lo[0]; x <= hi[0]; ++x) {
      for (auto y = lo[1]; y <= hi[1]; ++y) {
        for (auto z = lo[2]; z <= hi[2]; ++z) {
          const octomap::OcTreeKey key(x, y, z);
          const octomap::OcTreeNode* ours = tree.search(key);
          const octomap::OcTreeNode* theirs = free_mapper.tree().search(key);
          ASSERT_EQ(ours == nullptr, theirs == nullptr) << "scan " << k;
          if (ours != nullptr) {
            ASSERT_EQ(ours->getLogOdds(), theirs->getLogOdds()) << "scan " << k;
          }
        }
      }
    }
  }
  // AND most updates within the box found their voxel at its bound and skipped the descent
  EXPECT_GT(boxed.tree().updatesSkippedAtBounds(), 100'000U);
  EXPECT_EQ(free_mapper.tree().updatesSkippedAtBounds(), 0U);
}

TEST(Mapper, ABoxedTreeSettledOnceForManyScansIsTheTreeSettledAfterEach)
{
  // GIVEN two boxed mappers fed the same noisy scans, one whose tree is read after every
  // scan, one whose tree is read only now and then, settling all the scans since at once
  Mapper each(boxedConfig());
  Mapper batched(boxedConfig());
  const std::vector<Scan> scans = noisyScans(48, 29);
  std::size_t compared = 0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    ASSERT_TRUE(each.integrate(scans[k]).accepted);
    ASSERT_TRUE(batched.integrate(scans[k]).accepted);
    std::ostringstream after_each;
    each.tree().write(after_each);  // settled scan by scan
    if (k % 11 != 10 && k + 1 != scans.size()) {
      continue;
    }
    // THEN the tree settled at once is the same, node for node and log-odds for log-odds
    std::ostringstream at_once;
    batched.tree().write(at_once);
    ASSERT_EQ(at_once.str(), after_each.str()) << "after scan " << k;
    ++compared;
  }
  EXPECT_EQ(compared, 5U);
  EXPECT_LT(batched.nodes(), 8 * batched.classification().size()) << "the tree was pruned";
}

TEST(Mapper, AnImageWorkedOutWhileScansGoOnIsTheMapAsItWasWhenAsked)
{
  // GIVEN two boxed mappers fed the same noisy scans; every seventh scan one takes its image
  // at once, the other asks for it on a thread of its own (which takes the blocks unchanged
  // since its last image from it) and integrates three more scans before it looks at it
  Mapper now(boxedConfig());
  Mapper later(boxedConfig());
  const std::vector<Scan> scans = noisyScans(40, 31);
  std::atomic<int> done{0};
  std::size_t compared = 0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    ASSERT_TRUE(now.integrate(scans[k]).accepted);
    ASSERT_TRUE(later.integrate(scans[k]).accepted);
    if (k % 7 != 6 || k + 3 >= scans.size()) {
      continue;
    }
    const TreeImage expected = now.image(true);
    const std::shared_future<TreeImage> image = later.imageLater(true, [&done] { ++done; });
    for (std::size_t more = k + 1; more <= k + 3; ++more) {
      ASSERT_TRUE(now.integrate(scans[more]).accepted);
      ASSERT_TRUE(later.integrate(scans[more]).accepted);
    }
    k += 3;
    // THEN its image is the map as the scans before it left it, byte for byte
    EXPECT_EQ(image.get().binary, expected.binary) << "after scan " << k;
    EXPECT_EQ(image.get().data, expected.data);
    EXPECT_EQ(image.get().nodes, expected.nodes);
    EXPECT_EQ(image.get().memory_bytes, expected.memory_bytes);
    ++compared;
  }
  EXPECT_EQ(compared, 5U);
  EXPECT_EQ(done.load(), 5);
  // AND the tree, read after the last scan, holds them all
  std::ostringstream a, b;
  now.tree().write(a);
  later.tree().write(b);
  EXPECT_EQ(a.str(), b.str());
}

}  // namespace
}  // namespace quad::mapping
