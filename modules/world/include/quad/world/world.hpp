// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The simulated world: bounds, obstacles (boxes with yaw, vertical cylinders standing on the
/// ground, spheres), the ground plane z = 0, start and goal; distance and ray queries through
/// a uniform grid over x–y, so that they cost what is near, not what exists.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quad/geometry/so3.hpp"

namespace quad::world {

using geometry::Vector3;

struct Box {
  Vector3 center;      ///< [m] world
  Vector3 size;        ///< [m] edge lengths along the box's own x, y, z
  double yaw = 0.0;    ///< [rad] about world z
};

struct Cylinder {       ///< vertical, base on the ground
  double x = 0.0;       ///< [m] axis position
  double y = 0.0;
  double radius = 0.0;  ///< [m]
  double height = 0.0;  ///< [m] from z = 0
};

struct Sphere {
  Vector3 center;
  double radius = 0.0;
};

struct Obstacle {
  enum class Kind { kBox, kCylinder, kSphere };
  Kind kind = Kind::kBox;
  Box box;
  Cylinder cylinder;
  Sphere sphere;

  static Obstacle makeBox(const Box& b);
  static Obstacle makeCylinder(const Cylinder& c);
  static Obstacle makeSphere(const Sphere& s);

  /// Distance from p to the obstacle's surface; negative inside.
  double signedDistance(const Vector3& p) const;
  /// Smallest t in [0, t_max] with origin + t·direction on the surface (direction unit).
  std::optional<double> raycast(const Vector3& origin, const Vector3& direction, double t_max) const;
  /// Axis-aligned bounds [m].
  void bounds(Vector3& lo, Vector3& hi) const;
};

struct Bounds {
  Vector3 min;
  Vector3 max;
  bool contains(const Vector3& p) const;
};

/// What a ray hit.
struct RayHit {
  double distance = 0.0;  ///< [m]
  int obstacle = -1;      ///< obstacle index, or kGround
};

class World {
public:
  static constexpr int kGround = -2;  ///< RayHit::obstacle for the ground plane
  static constexpr int kBounds = -1;  ///< contact id for leaving the bounds

  /// Builds the index. `cell_size` [m] of the x–y grid; 0 picks one from the obstacles' sizes.
  World(Bounds bounds, Vector3 start, Vector3 goal, std::vector<Obstacle> obstacles,
        double cell_size = 0.0);

  const Bounds& bounds() const { return bounds_; }
  const Vector3& start() const { return start_; }
  const Vector3& goal() const { return goal_; }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  /// The same world (obstacles, bounds and index) with another start and goal: one vehicle's
  /// view of a world several fly in.
  World withStartAndGoal(const Vector3& start, const Vector3& goal) const;

  /// Indices of obstacles within `radius` of p (a sphere touching them), and kBounds when the
  /// sphere leaves the bounds sideways or through the top (the ground is contact, not
  /// collision). Sorted.
  std::vector<int> contacts(const Vector3& p, double radius) const;

  /// Nearest surface (obstacle or ground) along a unit direction within `max_range`.
  std::optional<RayHit> raycast(const Vector3& origin, const Vector3& direction, double max_range) const;

  /// The same by testing every obstacle: the reference the index is checked against.
  std::optional<RayHit> raycastBruteForce(const Vector3& origin, const Vector3& direction,
                                          double max_range) const;

private:
  int cellX(double x) const;
  int cellY(double y) const;
  const std::vector<int>& cell(int cx, int cy) const;

  Bounds bounds_;
  Vector3 start_;
  Vector3 goal_;
  std::vector<Obstacle> obstacles_;
  std::vector<int> unindexed_;  // obstacles reaching outside the grid: always tested
  double cell_size_ = 1.0;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<std::vector<int>> cells_;
  mutable std::vector<std::uint32_t> visited_;  // per obstacle, stamp of the last query
  mutable std::uint32_t stamp_ = 0;
};

}  // namespace quad::world
