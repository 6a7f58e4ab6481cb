// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/scene.hpp"

#include <array>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace quad::display {

namespace {
constexpr Colour kObstacle{0.55, 0.57, 0.62, 0.85};
constexpr Colour kGoal{0.15, 0.75, 0.3, 0.8};
}  // namespace

std::vector<Shape> obstacleShapes(const world::World& world)
{
  std::vector<Shape> shapes;
  shapes.reserve(world.obstacles().size());
  for (const auto& o : world.obstacles()) {
    Shape s;
    s.colour = kObstacle;
    switch (o.kind) {
      case world::Obstacle::Kind::kBox:
        s.kind = Shape::Kind::kBox;
        s.centre_W = o.box.center;
        s.q_WS = geometry::fromAxisAngle(Vector3::UnitZ(), o.box.yaw);
        s.size = o.box.size;
        break;
      case world::Obstacle::Kind::kCylinder:
        s.kind = Shape::Kind::kCylinder;
        s.centre_W = {o.cylinder.x, o.cylinder.y, o.cylinder.height / 2.0};
        s.size = {2.0 * o.cylinder.radius, 2.0 * o.cylinder.radius, o.cylinder.height};
        break;
      case world::Obstacle::Kind::kSphere:
        s.kind = Shape::Kind::kSphere;
        s.centre_W = o.sphere.center;
        s.size = Vector3::Constant(2.0 * o.sphere.radius);
        break;
    }
    shapes.push_back(s);
  }
  return shapes;
}

std::vector<Shape> mapShapes(const world::VoxelMap& map)
{
  // The voxels come sorted by z, then y, then x: the layers in order, a layer's rows in order,
  // each row's runs in order. A run grows into a rectangle while the next row holds a run of
  // the same x extent, and a rectangle into a box while the next layer holds one of the same
  // extent: the same sweep twice, over rows and then over layers.
  using Extent = std::array<int, 4>;  // x0, x1, y0, y1 (y0 = y1 for a run)
  struct Growing {
    int from = 0;  // the first row (layer) it covers
    int to = 0;    // the last
  };
  // Closes what the next row (layer) `at` did not extend, and extends or opens `found`.
  auto sweep = [](std::map<Extent, Growing>& open, const std::vector<Extent>& found, int at, auto&& close) {
    std::map<Extent, Growing> next;
    for (const Extent& e : found) {
      const auto grown = open.find(e);
      if (grown != open.end() && grown->second.to == at - 1) {
        next[e] = {grown->second.from, at};
        open.erase(grown);
      } else {
        next[e] = {at, at};
      }
    }
    for (const auto& [e, g] : open) {
      close(e, g);
    }
    open = std::move(next);
  };

  const auto& voxels = map.occupiedVoxels();
  const double res = map.resolution();
  std::vector<Shape> shapes;
  std::map<Extent, Growing> boxes;  // (x0, x1, y0, y1) -> the layers it covers so far
  auto closeBox = [&](const Extent& e, const Growing& layers) {
    const geometry::VoxelIndex lo(e[0], e[2], layers.from);
    const geometry::VoxelIndex hi(e[1], e[3], layers.to);
    Shape s;
    s.kind = Shape::Kind::kBox;
    s.centre_W = (map.grid().centre(lo) + map.grid().centre(hi)) / 2.0;
    s.size = Vector3(e[1] - e[0] + 1, e[3] - e[2] + 1, layers.to - layers.from + 1) * res;
    s.colour = kObstacle;
    shapes.push_back(s);
  };
  std::size_t k = 0;
  while (k < voxels.size()) {
    const int z = voxels[k].z();
    std::vector<Extent> rects;  // this layer's rectangles
    std::map<Extent, Growing> rows;  // (x0, x1, 0, 0) -> the rows it covers so far
    auto closeRect = [&](const Extent& e, const Growing& g) { rects.push_back({e[0], e[1], g.from, g.to}); };
    while (k < voxels.size() && voxels[k].z() == z) {
      const int y = voxels[k].y();
      std::vector<Extent> runs;
      while (k < voxels.size() && voxels[k].z() == z && voxels[k].y() == y) {
        const int x0 = voxels[k].x();
        int x1 = x0;
        for (++k; k < voxels.size() && voxels[k].z() == z && voxels[k].y() == y && voxels[k].x() == x1 + 1; ++k) {
          ++x1;
        }
        runs.push_back({x0, x1, 0, 0});
      }
      sweep(rows, runs, y, closeRect);
    }
    sweep(rows, {}, std::numeric_limits<int>::max(), closeRect);  // the layer's last rectangles
    sweep(boxes, rects, z, closeBox);
  }
  sweep(boxes, {}, std::numeric_limits<int>::max(), closeBox);
  return shapes;
}

std::vector<Shape> worldShapes(const world::World& world)
{
  std::vector<Shape> shapes = obstacleShapes(world);
  for (const auto& map : world.maps()) {
    const auto boxes = mapShapes(map);
    shapes.insert(shapes.end(), boxes.begin(), boxes.end());
  }
  return shapes;
}

Shape goalShape(const Vector3& goal_W, double radius)
{
  Shape s;
  s.kind = Shape::Kind::kSphere;
  s.centre_W = goal_W;
  s.size = Vector3::Constant(2.0 * radius);
  s.colour = kGoal;
  return s;
}

}  // namespace quad::display
