// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/scene.hpp"

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
