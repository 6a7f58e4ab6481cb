// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The simulated world: bounds, obstacles (boxes with yaw, vertical cylinders standing on the
/// ground, spheres), solid voxel maps of real scans, the ground plane z = 0, start and goal;
/// distance and ray queries through a uniform grid over x–y for the obstacles and voxel by
/// voxel through the maps, so that they cost what is near, not what exists.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quad/geometry/so3.hpp"
#include "quad/world/voxel_map.hpp"

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
  int obstacle = -1;      ///< solid id (World::describe), or kGround
};

class World {
public:
  static constexpr int kGround = -2;  ///< RayHit::obstacle for the ground plane
  static constexpr int kBounds = -1;  ///< contact id for leaving the bounds

  /// Builds the index. `cell_size` [m] of the x–y grid; 0 picks one from the obstacles' sizes.
  World(Bounds bounds, Vector3 start, Vector3 goal, std::vector<Obstacle> obstacles,
        double cell_size = 0.0, std::vector<VoxelMap> maps = {});

  const Bounds& bounds() const { return bounds_; }
  const Vector3& start() const { return start_; }
  const Vector3& goal() const { return goal_; }
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  const std::vector<VoxelMap>& maps() const { return maps_; }
  /// The solid id of map k: solids are numbered obstacles first, then maps.
  int mapId(std::size_t k) const { return static_cast<int>(obstacles_.size() + k); }
  /// A solid id (contact, ray hit) in words: "obstacle 3", "map 0 (office.bt)", "the ground",
  /// "the bounds".
  std::string describe(int id) const;
  /// The same world (obstacles, bounds and index) with another start and goal: one vehicle's
  /// view of a world several fly in.
  World withStartAndGoal(const Vector3& start, const Vector3& goal) const;

  /// The height [m] of what a vehicle of `radius` at p stands on, or would land on: the
  /// highest upward surface at or below p under the middle of its footprint (within radius / 2
  /// horizontally: its legs, not its propeller tips): the ground (z = 0), the top of a box or a
  /// cylinder, a sphere, or a map's voxel; below the ground, the bottom of the bounds.
  double supportHeight(const Vector3& p, double radius) const;

  /// Ids of the solids (obstacles, maps) within `radius` of p (a sphere touching them), and
  /// kBounds when the sphere leaves the bounds sideways or through the top. What the vehicle
  /// stands on (supportHeight) is contact, not collision: the ground, and every solid whose
  /// top lies at or below that surface. Sorted.
  std::vector<int> contacts(const Vector3& p, double radius) const;
  /// The same where the caller knows what the vehicle stands on (supportHeight(p, radius)).
  std::vector<int> contacts(const Vector3& p, double radius, double support) const;

  /// The nearest solid to a vehicle of `radius` at p, not counting what it stands on (as
  /// contacts does), if one is within `cap` [m].
  struct Nearest {
    double distance = 0.0;  ///< [m] from p to its surface; negative inside an obstacle, 0 inside a map's voxel
    int id = -1;            ///< its solid id
  };
  std::optional<Nearest> nearest(const Vector3& p, double radius, double cap) const;

  /// Nearest surface (obstacle or ground) along a unit direction within `max_range`.
  std::optional<RayHit> raycast(const Vector3& origin, const Vector3& direction, double max_range) const;

  /// The same by testing every obstacle: the reference the index is checked against.
  std::optional<RayHit> raycastBruteForce(const Vector3& origin, const Vector3& direction,
                                          double max_range) const;

private:
  /// Keeps in `best` the nearest hit of the ray in any map.
  void raycastMaps(const Vector3& origin, const Vector3& direction, double max_range, std::optional<RayHit>& best) const;
  /// Calls visit(id, obstacle) once for each obstacle that may lie within `reach` [m] of p
  /// horizontally (those of the index's cells there, and the unindexed).
  template <typename Visit>
  void forObstaclesNear(const Vector3& p, double reach, Visit&& visit) const;
  int cellX(double x) const;
  int cellY(double y) const;
  const std::vector<int>& cell(int cx, int cy) const;

  Bounds bounds_;
  Vector3 start_;
  Vector3 goal_;
  std::vector<Obstacle> obstacles_;
  std::vector<VoxelMap> maps_;
  std::vector<int> unindexed_;  // obstacles reaching outside the grid: always tested
  double cell_size_ = 1.0;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<std::vector<int>> cells_;
  mutable std::vector<std::uint32_t> visited_;  // per obstacle, stamp of the last query
  mutable std::uint32_t stamp_ = 0;
};

}  // namespace quad::world
