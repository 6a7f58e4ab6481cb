// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/scan_file.hpp"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>

#include "quad/common/params.hpp"
#include "quad/world/world_file.hpp"

namespace quad::world {
namespace {

namespace fs = std::filesystem;

const fs::path kGeb079 = fs::path(QUAD_CONFIG_DIR) / "worlds" / "scans" / "geb079.bt";

class ScanFile : public ::testing::Test {
protected:
  void SetUp() override
  {
    dir_ = fs::temp_directory_path() / ("quad_scan_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

enum class Ply { kAscii, kLittle, kBig };

/// A PLY of points as float x, y, z (and a colour and a face element, which readers skip).
void writePly(const fs::path& file, const std::vector<Vector3>& points, Ply format)
{
  std::ofstream out(file, std::ios::binary);
  const char* name = format == Ply::kAscii ? "ascii" : format == Ply::kLittle ? "binary_little_endian" : "binary_big_endian";
  out << "ply\nformat " << name << " 1.0\ncomment written by a test\nelement vertex " << points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&](auto v) {
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    if ((format == Ply::kBig) != (std::endian::native == std::endian::big)) {
      std::reverse(b, b + sizeof v);
    }
    out.write(b, sizeof v);
  };
  for (const Vector3& p : points) {
    if (format == Ply::kAscii) {
      out << static_cast<float>(p.x()) << ' ' << static_cast<float>(p.y()) << ' ' << static_cast<float>(p.z()) << " 200\n";
    } else {
      put(static_cast<float>(p.x()));
      put(static_cast<float>(p.y()));
      put(static_cast<float>(p.z()));
      put(std::uint8_t{200});
    }
  }
  if (format == Ply::kAscii) {
    out << "3 0 1 2\n";
  } else {
    put(std::uint8_t{3});
    for (std::int32_t i = 0; i < 3; ++i) {
      put(i);
    }
  }
}

/// A PCD of points as float x, y, z plus an intensity.
void writePcd(const fs::path& file, const std::vector<Vector3>& points, bool binary)
{
  std::ofstream out(file, std::ios::binary);
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\n"
         "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH "
      << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size() << "\nDATA "
      << (binary ? "binary" : "ascii") << "\n";
  for (const Vector3& p : points) {
    const float v[4] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()), 1.0F};
    if (binary) {
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    } else {
      out << v[0] << ' ' << v[1] << ' ' << v[2] << " 1\n";
    }
  }
}

std::vector<Vector3> centres(const VoxelMap& m)
{
  std::vector<Vector3> out;
  for (const VoxelIndex& v : m.occupiedVoxels()) {
    out.push_back(m.grid().centre(v));
  }
  return out;
}

std::string errorOf(const fs::path& file, const ScanPlacement& p = {})
{
  try {
    (void)loadScan(file, p);
  } catch (const ScanError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(ScanFile, TheRealBuildingLoadsEveryOccupiedVoxel)
{
  const VoxelMap m = loadScan(kGeb079, {});
  EXPECT_DOUBLE_EQ(m.resolution(), 0.08);
  // GIVEN OctoMap's own reading of the file  THEN  every voxel of every occupied leaf, and
  // no other, is solid
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(kGeb079.string()));
  std::size_t voxels = 0;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (tree.isNodeOccupied(*it)) {
      voxels += static_cast<std::size_t>(std::llround(std::pow(it.getSize() / 0.08, 3)));
      const octomap::point3d c = it.getCoordinate();
      EXPECT_TRUE(m.occupied(m.grid().toIndex(Vector3(c.x(), c.y(), c.z()))));
    }
  }
  EXPECT_EQ(m.occupiedVoxels().size(), voxels);
  Vector3 lo, hi;
  m.bounds(lo, hi);
  EXPECT_GT(hi.x() - lo.x(), 35.0);  // a 39 m floor
}

TEST_F(ScanFile, AnOctreeAndItsPointCloudsGiveTheSameVoxels)
{
  const VoxelMap bt = loadScan(kGeb079, {});
  const std::vector<Vector3> points = centres(bt);
  ScanPlacement at_its_resolution;
  at_its_resolution.resolution = 0.08;
  for (const Ply f : {Ply::kAscii, Ply::kLittle, Ply::kBig}) {
    const fs::path ply = dir_ / ("building" + std::to_string(static_cast<int>(f)) + ".ply");
    writePly(ply, points, f);
    EXPECT_EQ(loadScan(ply, at_its_resolution).occupiedVoxels(), bt.occupiedVoxels()) << ply;
  }
  for (const bool binary : {false, true}) {
    const fs::path pcd = dir_ / (binary ? "building_binary.pcd" : "building.pcd");
    writePcd(pcd, points, binary);
    EXPECT_EQ(loadScan(pcd, at_its_resolution).occupiedVoxels(), bt.occupiedVoxels()) << pcd;
  }
}

TEST_F(ScanFile, AnOtFileReadsAsItsBtTwin)
{
  octomap::OcTree tree(0.2);
  for (int i = 0; i < 30; ++i) {
    tree.updateNode(octomap::point3d(0.1F + 0.2F * static_cast<float>(i), 1.1F, 0.5F), true);
  }
  tree.updateNode(octomap::point3d(3.1F, 3.1F, 0.5F), false);  // free: not solid
  ASSERT_TRUE(tree.writeBinary((dir_ / "row.bt").string()));
  ASSERT_TRUE(tree.write((dir_ / "row.ot").string()));
  const VoxelMap bt = loadScan(dir_ / "row.bt", {});
  EXPECT_EQ(bt.occupiedVoxels().size(), 30U);
  EXPECT_EQ(loadScan(dir_ / "row.ot", {}).occupiedVoxels(), bt.occupiedVoxels());
}

TEST_F(ScanFile, APoseMovesAndTurnsTheVoxels)
{
  octomap::OcTree tree(0.1);
  const std::vector<VoxelIndex> source = {{0, 0, 0}, {3, 1, 0}, {5, -2, 4}};
  for (const VoxelIndex& v : source) {
    tree.updateNode(octomap::point3d(0.1F * static_cast<float>(v.x()) + 0.05F, 0.1F * static_cast<float>(v.y()) + 0.05F,
                                     0.1F * static_cast<float>(v.z()) + 0.05F),
                    true);
  }
  ASSERT_TRUE(tree.writeBinary((dir_ / "three.bt").string()));
  // GIVEN a translation of whole voxels and a quarter turn  THEN  voxel (x, y, z) lands at
  // (−y − 1, x, z) + the translation's voxels
  ScanPlacement p;
  p.position = Vector3(1.0, -2.0, 0.5);
  p.yaw = std::numbers::pi / 2.0;
  const VoxelMap moved = loadScan(dir_ / "three.bt", p);
  ASSERT_EQ(moved.occupiedVoxels().size(), 3U);
  for (const VoxelIndex& v : source) {
    EXPECT_TRUE(moved.occupied(VoxelIndex(-v.y() - 1, v.x(), v.z()) + VoxelIndex(10, -20, 5))) << v.transpose();
  }
  // a coarser resolution merges them into its own voxels
  p = {};
  p.resolution = 1.0;
  EXPECT_EQ(loadScan(dir_ / "three.bt", p).occupiedVoxels().size(), 2U);
}

TEST_F(ScanFile, ABadFileIsRefusedNamingIt)
{
  // truncated octree
  {
    std::ifstream in(kGeb079, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir_ / "cut.bt", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  EXPECT_NE(errorOf(dir_ / "cut.bt").find((dir_ / "cut.bt").string()), std::string::npos) << errorOf(dir_ / "cut.bt");
  std::ofstream(dir_ / "text.bt") << "hello\n";
  EXPECT_NE(errorOf(dir_ / "text.bt").find("not an OctoMap binary tree"), std::string::npos);
  EXPECT_NE(errorOf(dir_ / "missing.bt").find("cannot open"), std::string::npos);
  EXPECT_NE(errorOf(dir_ / "scan.xyz").find("expected .bt or .ot"), std::string::npos);

  ScanPlacement fine;
  fine.resolution = 0.1;
  std::ofstream(dir_ / "noz.ply") << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n";
  EXPECT_NE(errorOf(dir_ / "noz.ply", fine).find("noz.ply: line 6: element vertex has no scalar property z"), std::string::npos)
      << errorOf(dir_ / "noz.ply", fine);
  std::ofstream(dir_ / "short.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nend_header\n1 2 3\n4 5 6\n";
  EXPECT_NE(errorOf(dir_ / "short.ply", fine).find("the data ends early (point 2 of 3"), std::string::npos)
      << errorOf(dir_ / "short.ply", fine);
  std::ofstream(dir_ / "word.ply") << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                      "property float z\nend_header\n1 two 3\n";
  EXPECT_NE(errorOf(dir_ / "word.ply", fine).find("'two' is not a number"), std::string::npos);
  std::ofstream(dir_ / "packed.pcd") << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\n"
                                        "HEIGHT 1\nPOINTS 1\nDATA binary_compressed\n";
  EXPECT_NE(errorOf(dir_ / "packed.pcd", fine).find("binary_compressed is not read"), std::string::npos);
  writePly(dir_ / "fine.ply", {Vector3(1, 2, 3)}, Ply::kAscii);
  EXPECT_NE(errorOf(dir_ / "fine.ply").find("needs a resolution"), std::string::npos);
}

TEST_F(ScanFile, AWorldFileNamesItsMapsRelativeToItself)
{
  fs::create_directories(dir_ / "scans");
  writePly(dir_ / "scans" / "pillar.ply", {Vector3(2.05, 0.05, 0.05), Vector3(2.05, 0.05, 0.15)}, Ply::kLittle);
  std::ofstream(dir_ / "w.yaml") << "start: [2.01, 0.01, 1.01]\ngoal: [2.05, 0.05, 1.1]\n"
                                    "maps:\n  - {file: scans/pillar.ply, resolution: 0.1, pose: [0, 0, 1, 0]}\n";
  const World w = loadWorld(dir_ / "w.yaml");
  ASSERT_EQ(w.maps().size(), 1U);
  // the bounds default to the map's box, moved up 1 m by its pose
  EXPECT_TRUE(w.bounds().min.isApprox(Vector3(2.0, 0.0, 1.0))) << w.bounds().min.transpose();
  EXPECT_TRUE(w.bounds().max.isApprox(Vector3(2.1, 0.1, 1.2))) << w.bounds().max.transpose();

  std::ofstream(dir_ / "bad.yaml") << "bounds: {min: [0, 0, 0], max: [5, 5, 5]}\nstart: [1, 1, 0]\ngoal: [2, 2, 1]\n"
                                      "maps:\n  - {file: scans/none.bt}\n  - {file: scans/pillar.ply}\n  - {file: x.bt, size: 3}\n";
  try {
    (void)loadWorld(dir_ / "bad.yaml");
    FAIL() << "a world with bad maps loaded";
  } catch (const common::ConfigError& e) {
    const std::string all = e.what();
    EXPECT_NE(all.find("maps[0].file"), std::string::npos) << all;
    EXPECT_NE(all.find("none.bt: cannot open it"), std::string::npos) << all;
    EXPECT_NE(all.find("maps[1].file"), std::string::npos) << all;
    EXPECT_NE(all.find("needs a resolution"), std::string::npos) << all;
    EXPECT_NE(all.find("maps[2].size"), std::string::npos) << all;
  }
}

}  // namespace
}  // namespace quad::world
