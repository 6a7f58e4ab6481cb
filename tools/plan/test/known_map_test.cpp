// SPDX-License-Identifier: BSD-3-Clause
// The known-map optimum against geometry worked by hand, with the planner's own parameters.
#include "quad/plan/known_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/geometry/polyline.hpp"

namespace quad::plan {
namespace {

using world::Bounds;
using world::Obstacle;
using world::World;

/// The shipped planner's parameters in a world's box: x500 (0.35 m) plus the 0.3 m margin.
planning::PlanningParams paramsFor(const World& w)
{
  const common::Params p = common::defaultParams(planning::planningSchema());
  return planning::planningParamsFrom(p, w.bounds().min, w.bounds().max, 0.35);
}

/// The smallest clearance [m] of the path from any obstacle, sampled every 5 cm.
double clearance(const World& w, const std::vector<Vector3>& path)
{
  double least = 1e9;
  const double length = geometry::polylineLength(path);
  for (double s = 0.0; s <= length; s += 0.05) {
    for (const auto& o : w.obstacles()) {
      least = std::min(least, o.signedDistance(geometry::pointAlong(path, s)));
    }
  }
  return least;
}

TEST(KnownMap, AnOpenFieldIsCrossedInAStraightLine)
{
  const World w(Bounds{Vector3(-5, -10, 0), Vector3(45, 10, 10)}, Vector3(0, 0, 0), Vector3(40, 0, 2), {});
  const KnownMapPlan p = planOnKnownMap(w, paramsFor(w), true);
  ASSERT_EQ(p.status, planning::PlanStatus::kOk);
  EXPECT_NEAR(p.climb_m, 1.1, 1e-9);  // to the lowest cell centres, 1.1 m (1.0 m rounded up to a centre)
  EXPECT_NEAR(p.landing_m, 2.0, 1e-9);
  EXPECT_NEAR(p.path_m, (Vector3(40, 0, 2) - p.from).norm(), 1e-6);
  EXPECT_NEAR(p.optimum_m, p.climb_m + p.path_m + p.landing_m, 1e-12);
}

TEST(KnownMap, AWallIsOverflownJustAboveItsInflatedTop)
{
  // GIVEN a 6 m wall across the whole box
  const World w(Bounds{Vector3(-5, -10, 0), Vector3(45, 10, 10)}, Vector3(0, 0, 0), Vector3(40, 0, 2),
                {Obstacle::makeBox({Vector3(20, 0, 3), Vector3(0.4, 20, 6), 0.0})});
  const planning::PlanningParams params = paramsFor(w);
  // WHEN planned on the known map
  const KnownMapPlan p = planOnKnownMap(w, params, true);
  // THEN the path goes over, no shorter than over the top edge raised by the inflation radius
  // (less a cell of discretisation) and not much longer, and never touches the wall
  ASSERT_EQ(p.status, planning::PlanStatus::kOk);
  const double r = params.planner.vehicle_radius;
  const Vector3 edge_in(19.8 - r, 0, 6 + r), edge_out(20.2 + r, 0, 6 + r);
  const double lower = (edge_in - p.from).norm() + (edge_out - edge_in).norm() + (Vector3(40, 0, 2) - edge_out).norm();
  EXPECT_GT(p.path_m, lower - 0.3);
  EXPECT_LT(p.path_m, 1.05 * lower);
  EXPECT_GT(clearance(w, p.waypoints), 0.35);
}

TEST(KnownMap, ASealedGoalHasNoPath)
{
  const World w(Bounds{Vector3(-5, -10, 0), Vector3(45, 10, 10)}, Vector3(0, 0, 0), Vector3(25, 0, 2),
                {Obstacle::makeBox({Vector3(22, 0, 2), Vector3(0.4, 6.4, 4), 0.0}),
                 Obstacle::makeBox({Vector3(28, 0, 2), Vector3(0.4, 6.4, 4), 0.0}),
                 Obstacle::makeBox({Vector3(25, 3, 2), Vector3(6.4, 0.4, 4), 0.0}),
                 Obstacle::makeBox({Vector3(25, -3, 2), Vector3(6.4, 0.4, 4), 0.0}),
                 Obstacle::makeBox({Vector3(25, 0, 4.2), Vector3(6.4, 6.4, 0.4), 0.0})});
  const KnownMapPlan p = planOnKnownMap(w, paramsFor(w), true);
  EXPECT_EQ(p.status, planning::PlanStatus::kGoalEnclosed);
  EXPECT_TRUE(p.waypoints.empty());
}

}  // namespace
}  // namespace quad::plan
