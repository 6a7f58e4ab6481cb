// SPDX-License-Identifier: BSD-3-Clause
// The lattice's box from the world's, the altitude band and the geofence.
#include "quad/planning/planning_params.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "quad/common/params.hpp"

namespace quad::planning {
namespace {

PlanningParams read(const std::string& yaml)
{
  return planningParamsOf(common::parseParams(yaml, "planning.yaml", planningSchema()));
}

const Vector3 kWorldMin(-5, -10, 0);
const Vector3 kWorldMax(40, 10, 12);
constexpr double kRadius = 0.35;  // + safety_margin 0.3: inflation 0.65

TEST(PlanningParams, WithoutAGeofenceTheLatticeCoversTheWorldLessTheInflation)
{
  PlanningParams p = read("safety_margin: 0.3\nground_clearance: 1.0\n");
  fitToWorld(p, kWorldMin, kWorldMax, kRadius, "planning.yaml");
  EXPECT_FALSE(p.geofence.bounded());
  EXPECT_TRUE(p.bounds_min.isApprox(Vector3(-4.35, -9.35, 1.0)));
  EXPECT_TRUE(p.bounds_max.isApprox(Vector3(39.35, 9.35, 11.35)));
}

TEST(PlanningParams, TheShippedConfigIsReadWholeByThePlannerCoreAsQuadPlanReadsIt)
{
  // configs/planning.yaml serves the node and `quad plan` (the known-map optimum) alike: every
  // key in it is the core's.
  const PlanningParams p = planningParamsOf(common::loadParams(QUAD_CONFIG_DIR "/planning.yaml", planningSchema()));
  EXPECT_DOUBLE_EQ(p.replan_period_s, 0.2);
  EXPECT_DOUBLE_EQ(p.state_rate, 0.0);  // every state
}

TEST(PlanningParams, TheGeofenceLessTheMarginClipsTheLattice)
{
  PlanningParams p = read("safety_margin: 0.3\ngeofence: {min: [0, -3, -1], max: [50, 3, 6]}\n");
  fitToWorld(p, kWorldMin, kWorldMax, kRadius, "planning.yaml");
  // x: the world's inset below, the fence's inset above the world's own; y: the fence on both
  // sides; z: the ground clearance below, the fence above.
  EXPECT_TRUE(p.bounds_min.isApprox(Vector3(0.3, -2.7, 1.0)));
  EXPECT_TRUE(p.bounds_max.isApprox(Vector3(39.35, 2.7, 5.7)));
}

TEST(PlanningParams, AnInvertedOrTooThinGeofenceIsRefusedNamingTheKey)
{
  try {
    read("geofence: {min: [0, 3, 0], max: [50, -3, 6]}\n");
    ADD_FAILURE() << "an inverted geofence was accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("planning.yaml:geofence.min: [0, 3, 0]: not below geofence.max on the y axis"),
              std::string::npos)
        << e.what();
  }
  PlanningParams p = read("safety_margin: 0.3\ngeofence: {min: [0, -0.35, 0], max: [50, 0.35, 6]}\n");
  EXPECT_THROW(fitToWorld(p, kWorldMin, kWorldMax, kRadius, "planning.yaml"), common::ConfigError);
}

TEST(PlanningParams, TheKnownFreeTubeIsTheVehicleAndItsMarginAndTheVehiclesOwnVoxelsTubeCountsAsFree)
{
  // GIVEN a 0.1 m margin on 0.2 m voxels, for a vehicle of radius 0.35 m
  PlanningParams p = read("safety_margin: 0.3\nresolution: 0.2\nknown_free: {margin: 0.1}\n");
  fitToWorld(p, kWorldMin, kWorldMax, kRadius, "planning.yaml");
  // THEN the tube is 0.45 m, and every voxel it reads around the voxel the vehicle is in (whose
  // centre is up to half a diagonal away) counts as free: the vehicle flew there in such a tube
  EXPECT_NEAR(p.known_space.radius, 0.45, 1e-12);
  EXPECT_GE(p.known_space.own_radius, 0.45 + 0.5 * std::sqrt(3.0) * 0.2 - 1e-12);
}

TEST(PlanningParams, AKnownFreeMarginReachingPastTheInflationIsRefusedNamingTheKey)
{
  PlanningParams p = read("safety_margin: 0.3\nresolution: 0.2\nknown_free: {margin: 0.2}\n");
  try {
    fitToWorld(p, kWorldMin, kWorldMax, kRadius, "planning.yaml");
    ADD_FAILURE() << "a margin of 0.2 m (0.55 m, plus 0.17 m, past the 0.65 m inflation) was accepted";
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("planning.yaml:known_free.margin: 0.2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace quad::planning
