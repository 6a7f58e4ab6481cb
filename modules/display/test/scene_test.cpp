// SPDX-License-Identifier: BSD-3-Clause
#include "quad/display/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quad::display {
namespace {

/// Whether p lies inside the shape (boxes and spheres as drawn: centre, axes, size).
bool insideShape(const Shape& s, const Vector3& p)
{
  const Vector3 local = geometry::rotate(s.q_WS.conjugate(), p - s.centre_W);
  const Vector3 half = s.size / 2.0;
  switch (s.kind) {
    case Shape::Kind::kBox:
      return std::abs(local.x()) <= half.x() && std::abs(local.y()) <= half.y() && std::abs(local.z()) <= half.z();
    case Shape::Kind::kCylinder:
      return local.head<2>().norm() <= half.x() && std::abs(local.z()) <= half.z();
    case Shape::Kind::kSphere:
      return local.norm() <= half.x();
  }
  return false;
}

TEST(Scene, EachShapeCoversExactlyItsObstacle)
{
  std::vector<world::Obstacle> obstacles{
      world::Obstacle::makeBox({{10, 1, 2}, {2, 3, 4}, 0.3}),
      world::Obstacle::makeCylinder({20, -2, 0.4, 8}),
      world::Obstacle::makeSphere({{30, 0, 3}, 1.2}),
  };
  const world::World w({{-5, -10, 0}, {60, 10, 10}}, {0, 0, 0}, {50, 0, 2}, obstacles);
  const auto shapes = obstacleShapes(w);
  ASSERT_EQ(shapes.size(), obstacles.size());
  // Points sampled around each obstacle are inside its shape exactly when inside the obstacle
  // (away from the surface, where rounding decides).
  std::mt19937 rng(5);
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    Vector3 lo, hi;
    obstacles[k].bounds(lo, hi);
    std::uniform_real_distribution<double> ux(lo.x() - 1, hi.x() + 1), uy(lo.y() - 1, hi.y() + 1),
        uz(std::max(lo.z() - 1, 0.0), hi.z() + 1);
    for (int i = 0; i < 2000; ++i) {
      const Vector3 p(ux(rng), uy(rng), uz(rng));
      const double d = obstacles[k].signedDistance(p);
      if (std::abs(d) > 1e-6) {
        EXPECT_EQ(insideShape(shapes[k], p), d < 0.0) << k << " at " << p.transpose();
      }
    }
  }
}

TEST(Scene, TheGoalIsASphereOfItsRadius)
{
  const Shape g = goalShape({1, 2, 3}, 0.25);
  EXPECT_EQ(g.kind, Shape::Kind::kSphere);
  EXPECT_EQ(g.centre_W, Vector3(1, 2, 3));
  EXPECT_EQ(g.size, Vector3::Constant(0.5));
}

}  // namespace
}  // namespace quad::display
