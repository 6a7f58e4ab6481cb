// SPDX-License-Identifier: BSD-3-Clause
#include "quad/world/scan_file.hpp"

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>

#include "quad/world/point_cloud_file.hpp"

namespace quad::world {

namespace {

namespace fs = std::filesystem;

/// Fills the world voxels of an occupied source box (centre, edge) moved by the placement.
class Voxeliser {
public:
  explicit Voxeliser(const ScanPlacement& placement)
      : grid_(placement.resolution),
        placement_(placement),
        c_(std::cos(placement.yaw)),
        s_(std::sin(placement.yaw)),
        turned_(std::abs(s_) > 1e-12 || c_ < 0.0)
  {
  }

  void fill(const Vector3& centre, double edge)
  {
    // Samples at spacing ≤ resolution cover every voxel of an unturned box; a turned box
    // straddles voxel faces anywhere, so it is sampled twice as densely.
    const double spacing = grid_.resolution() / (turned_ ? 2.0 : 1.0);
    const int n = std::max(1, static_cast<int>(std::ceil(edge / spacing - 1e-9)));
    const double step = edge / n;
    const Vector3 first = centre - Vector3::Constant(0.5 * edge - 0.5 * step);
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const Vector3 p = first + step * Vector3(i, j, k);
          const Vector3 w(c_ * p.x() - s_ * p.y(), s_ * p.x() + c_ * p.y(), p.z());
          voxels_.push_back(grid_.toIndex(w + placement_.position));
        }
      }
    }
  }

  VoxelMap take(const fs::path& file)
  {
    if (voxels_.empty()) {
      throw ScanError(file.string() + ": nothing in it is occupied");
    }
    try {
      return VoxelMap(file.string(), grid_, std::move(voxels_));
    } catch (const std::invalid_argument& e) {
      throw ScanError(e.what());
    }
  }

private:
  geometry::VoxelGrid grid_;
  ScanPlacement placement_;
  double c_;
  double s_;
  bool turned_;
  std::vector<VoxelIndex> voxels_;
};

/// OctoMap reports what it reads, and why it fails, on std::cerr: kept here while it reads, so
/// that a good file says nothing and a bad one's reason joins the error. std::cerr is the
/// process's: one capture at a time (the modules of a container are built on threads of their
/// own, and each may read a scan), or one would restore another's buffer, gone by then.
class CerrCapture {
public:
  CerrCapture() : hold_(capturing()), previous_(std::cerr.rdbuf(text_.rdbuf())) {}
  ~CerrCapture() { std::cerr.rdbuf(previous_); }
  CerrCapture(const CerrCapture&) = delete;
  CerrCapture& operator=(const CerrCapture&) = delete;

  /// The last line OctoMap wrote that says what went wrong, or "".
  std::string reason() const
  {
    std::istringstream lines(text_.str());
    std::string why;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("ERROR: ", 0) == 0) {
        why = ": " + line.substr(7);
      }
    }
    return why;
  }

private:
  static std::mutex& capturing()
  {
    static std::mutex mutex;
    return mutex;
  }

  std::lock_guard<std::mutex> hold_;
  std::ostringstream text_;
  std::streambuf* previous_;
};

std::unique_ptr<octomap::OcTree> readOcTree(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ScanError(file.string() + ": cannot open it");
  }
  if (file.extension() == ".bt") {
    std::string first;
    std::getline(in, first);
    if (first.rfind("# Octomap OcTree binary file", 0) != 0) {
      throw ScanError(file.string() + ": not an OctoMap binary tree (.bt): it does not start with '# Octomap OcTree binary file'");
    }
    in.seekg(0);
    auto tree = std::make_unique<octomap::OcTree>(0.1);
    const CerrCapture octomap_says;
    if (!tree->readBinary(in)) {
      throw ScanError(file.string() + ": OctoMap could not read it (a malformed or truncated .bt)" + octomap_says.reason());
    }
    return tree;
  }
  std::string first;
  std::getline(in, first);
  if (first.rfind("# Octomap OcTree file", 0) != 0) {
    throw ScanError(file.string() + ": not an OctoMap tree (.ot): it does not start with '# Octomap OcTree file'");
  }
  in.seekg(0);
  const CerrCapture octomap_says;
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(in));
  if (!tree) {
    throw ScanError(file.string() + ": OctoMap could not read it (a malformed or truncated .ot)" + octomap_says.reason());
  }
  if (auto* occupancy = dynamic_cast<octomap::OcTree*>(tree.get())) {
    tree.release();
    return std::unique_ptr<octomap::OcTree>(occupancy);
  }
  throw ScanError(file.string() + ": an OctoMap of type " + tree->getTreeType() + ", not an OcTree of occupancy");
}

}  // namespace

VoxelMap loadScan(const fs::path& file, const ScanPlacement& placement)
{
  const std::string ext = file.extension().string();
  if (!placement.position.allFinite() || !std::isfinite(placement.yaw) || !std::isfinite(placement.resolution) ||
      placement.resolution < 0.0) {
    throw ScanError(file.string() + ": the placement must be finite, its resolution ≥ 0");
  }
  if (ext == ".bt" || ext == ".ot") {
    const auto tree = readOcTree(file);
    ScanPlacement p = placement;
    if (p.resolution == 0.0) {
      p.resolution = tree->getResolution();
    }
    Voxeliser v(p);
    for (auto it = tree->begin_leafs(); it != tree->end_leafs(); ++it) {
      if (tree->isNodeOccupied(*it)) {
        const octomap::point3d c = it.getCoordinate();
        v.fill(Vector3(c.x(), c.y(), c.z()), it.getSize());
      }
    }
    return v.take(file);
  }
  if (ext == ".ply" || ext == ".pcd") {
    if (placement.resolution <= 0.0) {
      throw ScanError(file.string() + ": a point cloud needs a resolution [m] to be voxelised at");
    }
    std::vector<Vector3> points;
    try {
      points = readPointCloud(file);
    } catch (const PointCloudError& e) {
      throw ScanError(e.what());
    }
    // A point is a voxel of the cloud's own grid at that resolution, placed like a leaf.
    const geometry::VoxelGrid own(placement.resolution);
    Voxeliser v(placement);
    for (const Vector3& p : points) {
      v.fill(own.centre(own.toIndex(p)), placement.resolution);
    }
    return v.take(file);
  }
  throw ScanError(file.string() + ": not a scan: expected .bt or .ot (OctoMap) or .ply or .pcd (point cloud)");
}

}  // namespace quad::world
