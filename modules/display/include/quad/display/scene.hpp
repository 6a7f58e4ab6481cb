// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The world's obstacles, its scanned maps and the goal as shapes a viewer draws (Foxglove's
/// scene primitives): each a box, a cylinder or a sphere, posed in the world frame.

#include <vector>

#include "quad/geometry/quaternion.hpp"
#include "quad/world/world.hpp"

namespace quad::display {

using geometry::Quaternion;
using geometry::Vector3;

struct Colour {
  double r = 1.0;  ///< [0, 1]
  double g = 1.0;
  double b = 1.0;
  double a = 1.0;  ///< opacity
};

struct Shape {
  enum class Kind { kBox, kCylinder, kSphere };
  Kind kind = Kind::kBox;
  Vector3 centre_W = Vector3::Zero();  ///< [m] the shape's centre (a cylinder's half way up)
  Quaternion q_WS;                     ///< the shape's axes in the world (a cylinder along z)
  Vector3 size = Vector3::Ones();      ///< [m] edge lengths, or diameters in x, y and height in z
  Colour colour;
};

/// One shape per obstacle, in the world's order: a box with its yaw, a vertical cylinder
/// standing on the ground, a sphere.
std::vector<Shape> obstacleShapes(const world::World& world);

/// The occupied voxels of a scanned map as boxes: each voxel in exactly one box, no two boxes
/// overlapping. Runs of voxels along x become one box, runs of the same extent in neighbouring
/// rows one box again, and rectangles of the same extent in neighbouring layers one box, so a
/// wall of voxels is a few boxes, not thousands.
std::vector<Shape> mapShapes(const world::VoxelMap& map);

/// Everything solid the world holds: obstacleShapes(), then each map's mapShapes() in the
/// world's order.
std::vector<Shape> worldShapes(const world::World& world);

/// The goal: a sphere of `radius` [m] at `goal_W`.
Shape goalShape(const Vector3& goal_W, double radius);

}  // namespace quad::display
