// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Point cloud files as scanners and tools write them: PLY (Turk 1994; `ascii`,
/// `binary_little_endian` and `binary_big_endian`) and PCD (the Point Cloud Library's format;
/// `ascii` and `binary`). Only the points' x, y, z are read; every other property (colour,
/// normals, intensity) and every other element (faces) is skipped.

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::world {

/// A file that is not a point cloud this reader understands: the message names the file and
/// what is wrong (`scan.ply: line 3: element vertex has no property z`).
class PointCloudError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The points [m, in the file's frame] of a .ply or .pcd file (by its extension). Throws
/// PointCloudError for an unreadable, truncated or malformed file or a format it does not read
/// (PCD's binary_compressed). A point that is not finite (no return, as organised clouds store
/// it) is dropped.
std::vector<geometry::Vector3> readPointCloud(const std::filesystem::path& file);

}  // namespace quad::world
