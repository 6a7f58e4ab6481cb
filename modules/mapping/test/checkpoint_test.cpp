// SPDX-License-Identifier: BSD-3-Clause
// A mapper started again from its checkpoint goes on exactly as the one that wrote it would
// have; a bad checkpoint is refused naming the file, and leaves the mapper empty.
#include "quad/mapping/checkpoint.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "scans.hpp"
#include "scratch.hpp"

namespace quad::mapping {
namespace {

namespace fs = std::filesystem;

class Checkpoint : public ::testing::Test {
protected:
  void TearDown() override { fs::remove_all(dir_); }

  /// The message of what `f` throws, empty when it throws nothing.
  template <class F>
  static std::string thrown(F&& f)
  {
    try {
      f();
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_ = quad::test::scratchDir("quad_checkpoint_test");
};

TEST_F(Checkpoint, AResumedMapperGoesOnExactlyAsTheOneThatWroteIt)
{
  const world::World world = test::boxWorld();
  std::mt19937_64 rng(11);
  std::vector<Scan> scans;
  for (int k = 0; k < 6; ++k) {
    scans.push_back(test::scanFrom(world, Vector3(-1.0 + 0.5 * k, 0.3 * k - 1.0, 1.5), 0.2 * k, rng));
  }
  // Unbounded, and boxed: a boxed mapper works its changes out from each voxel's log-odds,
  // which a resumed one reads back from the tree.
  MapperConfig boxed;
  boxed.box = std::make_pair(Vector3(-2.0, -6.0, 0.0), Vector3(8.0, 6.0, 4.0));
  for (const MapperConfig& config : {MapperConfig{}, boxed}) {
    SCOPED_TRACE(config.box ? "boxed" : "unbounded");
    Mapper original(config);
    for (std::size_t k = 0; k < 3; ++k) {
      original.integrate(scans[k]);
    }
    const fs::path file = dir_ / "map.checkpoint";
    writeCheckpoint(file, original, {1'000'042, 3'500'000'000});
    EXPECT_FALSE(fs::exists(dir_ / "map.checkpoint.tmp"));

    Mapper resumed(config);
    const auto meta = readCheckpoint(file, resumed);
    ASSERT_TRUE(meta.has_value());
    EXPECT_EQ(meta->next_update_seq, 1'000'042U);
    EXPECT_EQ(meta->stamp_ns, 3'500'000'000);
    test::expectSameClassification(original.classification(), resumed.classification());
    // The log-odds came along: the same scans change the same voxels in both, and leave the
    // same tree.
    for (std::size_t k = 3; k < 6; ++k) {
      const auto a = original.integrate(scans[k]);
      const auto b = resumed.integrate(scans[k]);
      EXPECT_FALSE(a.changes.empty());
      test::expectSameClassification(a.changes, b.changes);
    }
    std::ostringstream ours, theirs;
    original.tree().write(ours);
    resumed.tree().write(theirs);
    EXPECT_EQ(ours.str(), theirs.str());
  }
}

TEST_F(Checkpoint, NoFileIsNoCheckpointAndBadOnesAreRefusedNamingTheFile)
{
  Mapper mapper(MapperConfig{});
  EXPECT_FALSE(readCheckpoint(dir_ / "none", mapper).has_value());

  std::ofstream(dir_ / "text") << "resolution: 0.2\n";
  EXPECT_EQ(thrown([&] { readCheckpoint(dir_ / "text", mapper); }), (dir_ / "text").string() + ": not a quad map checkpoint");

  const world::World world = test::boxWorld();
  std::mt19937_64 rng(2);
  Mapper coarse(MapperConfig{.resolution = 0.4});
  coarse.integrate(test::scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  writeCheckpoint(dir_ / "coarse", coarse, {7, 0});
  EXPECT_EQ(thrown([&] { readCheckpoint(dir_ / "coarse", mapper); }),
            (dir_ / "coarse").string() + ": a map of resolution 0.4 m; the mapper's is 0.2 m");

  Mapper fine(MapperConfig{});
  fine.integrate(test::scanFrom(world, Vector3(0, 0, 1.5), 0.0, rng));
  writeCheckpoint(dir_ / "whole", fine, {7, 0});
  const auto size = fs::file_size(dir_ / "whole");
  fs::copy_file(dir_ / "whole", dir_ / "cut");
  fs::resize_file(dir_ / "cut", size / 2);
  EXPECT_NE(thrown([&] { readCheckpoint(dir_ / "cut", mapper); }).find((dir_ / "cut").string() + ": the octree"),
            std::string::npos);
  EXPECT_EQ(mapper.nodes(), 0U);  // left empty
  EXPECT_TRUE(readCheckpoint(dir_ / "whole", mapper).has_value());
}

}  // namespace
}  // namespace quad::mapping
