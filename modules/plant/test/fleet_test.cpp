// SPDX-License-Identifier: BSD-3-Clause
#include "quad/plant/fleet.hpp"
#include "quad/plant/fleet_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "quad/common/params.hpp"
#include "quad/common/payload_header.hpp"
#include "test_vehicle.hpp"

namespace quad::plant {
namespace {

using world::Bounds;
using world::Obstacle;
using world::World;

World openSky()
{
  return World(Bounds{Vector3(-20, -20, 0), Vector3(20, 20, 20)}, Vector3(0, 0, 0), Vector3(10, 0, 2), {});
}

World corridor()
{
  return World(Bounds{Vector3(-10, -10, 0), Vector3(60, 10, 20)}, Vector3(0, 0, 0), Vector3(50, 0, 2),
               {Obstacle::makeBox({Vector3(6, 0, 5), Vector3(2, 4, 10), 0.0}),
                Obstacle::makeCylinder({20, 5, 0.5, 8})});
}

/// No gravity and no range noise: vehicles without commands keep their motion, and ranges
/// have closed forms.
SimulationConfig weightless()
{
  SimulationConfig config;
  config.gravity_W.setZero();
  config.depth.noise_std = 0.0;
  return config;
}

FleetVehicle vehicleAt(std::uint32_t id, const Vector3& start)
{
  return {id, test::dragFreeVehicle(), start, Vector3(10, 0, 2), {}};
}

RigidBodyState moving(const Vector3& p, const Vector3& v)
{
  RigidBodyState s;
  s.p_W = p;
  s.v_W = v;
  return s;
}

TEST(Fleet, AFleetOfOneFliesAsTheLoneSimulationOfItsSeed)
{
  SimulationConfig config;
  config.seed = 5;
  const World world = corridor();
  Fleet fleet({{2, test::dragFreeVehicle(), world.start(), world.goal(), {}}}, world, config);
  Simulation lone(test::dragFreeVehicle(), world, config);
  int frames = 0;
  for (int k = 0; k < 1500; ++k) {
    const std::vector<StepOutputs> out = fleet.step();
    const StepOutputs alone = lone.step();
    ASSERT_EQ(out.size(), 1U);
    ASSERT_EQ(out[0].state.has_value(), alone.state.has_value());
    ASSERT_EQ(out[0].imu.has_value(), alone.imu.has_value());
    ASSERT_EQ(out[0].depth.has_value(), alone.depth.has_value());
    if (alone.imu) {
      ASSERT_EQ(out[0].imu->sample.specific_force_B, alone.imu->sample.specific_force_B) << "step " << k;
      ASSERT_EQ(out[0].imu->sample.angular_rate_B, alone.imu->sample.angular_rate_B) << "step " << k;
    }
    if (alone.depth) {
      ++frames;
      ASSERT_EQ(out[0].depth->scan.points_S, alone.depth->scan.points_S) << "step " << k;
    }
  }
  EXPECT_EQ(fleet.vehicle(0).state().p_W, lone.state().p_W);
  EXPECT_EQ(frames, 15);
  EXPECT_TRUE(std::isinf(fleet.minimumSeparation()));
}

TEST(Fleet, VehiclesThatMeetCollideOnceEachAtTheFirstStepTheirSpheresOverlap)
{
  Fleet fleet({vehicleAt(1, {0, 0, 5}), vehicleAt(2, {4, 0, 5})}, openSky(), weightless());
  fleet.vehicle(0).setState(moving({0, 0, 5}, {1, 0, 0}));
  fleet.vehicle(1).setState(moving({4, 0, 5}, {-1, 0, 0}));
  // Two 0.35 m spheres closing at 2 m/s from 4 m: they touch at t = (4 - 0.7) / 2 = 1.65 s,
  // pass through each other (contacts are counted, not resolved) and part at 2.35 s.
  std::optional<std::int64_t> first_overlap;
  std::vector<std::vector<SimEventRecord>> hits(2);
  for (int k = 0; k < 4000; ++k) {
    const std::vector<StepOutputs> out = fleet.step();
    const double gap = (fleet.vehicle(0).state().p_W - fleet.vehicle(1).state().p_W).norm() - 0.7;
    if (gap < 0.0 && !first_overlap) {
      first_overlap = fleet.timeNs();
    }
    for (std::size_t i = 0; i < 2; ++i) {
      for (const SimEventRecord& e : out[i].events) {
        if (e.kind == SimEventRecord::Kind::kCollision) {
          hits[i].push_back(e);
        }
      }
    }
  }
  ASSERT_TRUE(first_overlap.has_value());
  EXPECT_NEAR(static_cast<double>(*first_overlap) * 1e-9, 1.65, 0.0011);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(hits[i].size(), 1U) << "vehicle " << fleet.id(i);
    EXPECT_EQ(hits[i][0].t_ns, *first_overlap);
    EXPECT_EQ(hits[i][0].other_vehicle, fleet.id(1 - i));
    EXPECT_EQ(fleet.collisionCount(i), 1U);
    EXPECT_EQ(fleet.vehicle(i).collisionCount(), 0U);  // no obstacle was touched
  }
  // The centres crossed: the least separation is minus both radii, to a step's travel.
  EXPECT_NEAR(fleet.minimumSeparation(), -0.7, 0.002);
}

/// The range along a unit ray from o to a sphere, when it hits the sphere's outside.
std::optional<double> rangeToSphere(const Vector3& o, const Vector3& d, const Vector3& centre, double radius)
{
  const Vector3 oc = centre - o;
  const double b = d.dot(oc);
  const double disc = b * b - (oc.squaredNorm() - radius * radius);
  if (disc < 0.0 || b - std::sqrt(disc) < 0.0) {
    return std::nullopt;
  }
  return b - std::sqrt(disc);
}

TEST(Fleet, ADepthCameraSeesAnotherVehicleAsItsSphere)
{
  const SimulationConfig config = weightless();
  const Vector3 ahead(3.0, 0.4, 5.0);
  // At rest and weightless, without commands: both stay where they start.
  Fleet fleet({vehicleAt(1, {0, 0, 5}), vehicleAt(2, ahead)}, openSky(), config);
  std::vector<StepOutputs> out;
  while (!(out = fleet.step())[0].depth) {
  }
  const DepthScan& scan = out[0].depth->scan;
  const DepthCamera camera(config.depth);
  const World world = openSky();
  const geometry::Matrix3 R_WS = geometry::toMatrix(scan.sensor_W.q);
  int on_body = 0;
  for (std::size_t i = 0; i < scan.points_S.size(); ++i) {
    const Vector3 d_W = R_WS * camera.directions_S()[i];
    std::optional<double> expected;
    if (const auto hit = world.raycast(scan.sensor_W.p, d_W, config.depth.max_range)) {
      expected = hit->distance;
    }
    const auto body = rangeToSphere(scan.sensor_W.p, d_W, ahead, 0.35);
    if (body && (!expected || *body < *expected)) {
      expected = body;
      ++on_body;
    }
    const double range = expected.value_or(config.depth.max_range * DepthCamera::kMissFactor);
    ASSERT_NEAR(scan.points_S[i].cast<double>().norm(), range, 1e-4) << "ray " << i;
  }
  EXPECT_GT(on_body, 0);
  EXPECT_EQ(scan.hits, static_cast<int>(std::count_if(scan.points_S.begin(), scan.points_S.end(), [&](const auto& p) {
              return static_cast<double>(p.norm()) < config.depth.max_range;
            })));
}

std::string refusal(std::vector<FleetVehicle> vehicles)
{
  try {
    Fleet fleet(std::move(vehicles), openSky(), {});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Fleet, RefusesNoVehicleARepeatedIdAndVehiclesThatStartInContact)
{
  const auto says = [](const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
  };
  EXPECT_PRED2(says, refusal({}), "at least one vehicle");
  EXPECT_PRED2(says, refusal({vehicleAt(3, {0, 0, 0}), vehicleAt(3, {5, 0, 0})}), "vehicle id 3 appears twice");
  EXPECT_PRED2(says, refusal({vehicleAt(1, {0, 0, 0}), vehicleAt(2, {0.5, 0, 0})}),
               "vehicles 1 and 2 start 0.500 m apart, in contact");
  EXPECT_EQ(refusal({vehicleAt(1, {0, 0, 0}), vehicleAt(2, {0.7, 0, 0})}), "");  // touching is not yet contact
}

const std::filesystem::path kVehicle = std::filesystem::path(QUAD_CONFIG_DIR) / "vehicles/x500.yaml";

std::vector<FleetVehicle> fleetOf(const std::string& yaml)
{
  return parseFleet(yaml, "fleet.yaml", QUAD_CONFIG_DIR, openSky(), kVehicle);
}

std::string fleetRefusal(const std::string& yaml)
{
  try {
    fleetOf(yaml);
  } catch (const common::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(FleetFile, ReadsEachVehicleWithItsDefaults)
{
  const auto fleet = fleetOf(
      "vehicles:\n"
      "  - {id: 1, start: [0, 0, 0]}\n"
      "  - {id: 7, start: [2, 3, 1.5], goal: [-5, 4, 2], vehicle: vehicles/x500.yaml}\n");
  ASSERT_EQ(fleet.size(), 2U);
  EXPECT_EQ(fleet[0].id, 1U);
  EXPECT_EQ(fleet[0].start, Vector3(0, 0, 0));
  EXPECT_EQ(fleet[0].goal, openSky().goal());  // the world's
  EXPECT_EQ(fleet[0].params.radius, vehicle::loadVehicle(kVehicle).radius);
  EXPECT_TRUE(fleet[0].schedule.empty());
  EXPECT_EQ(fleet[1].id, 7U);
  EXPECT_EQ(fleet[1].start, Vector3(2, 3, 1.5));
  EXPECT_EQ(fleet[1].goal, Vector3(-5, 4, 2));
}

TEST(FleetFile, NamesTheKeyAndValueOfEveryProblem)
{
  const auto says = [](const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
  };
  EXPECT_PRED2(says, fleetRefusal("vehicles: []\n"), "fleet.yaml:vehicles: []: expected a list of at least one vehicle");
  EXPECT_PRED2(says, fleetRefusal("vehicle: [{id: 1, start: [0, 0, 0]}]\n"), "fleet.yaml:vehicle: ");
  const std::string many = fleetRefusal(
      "vehicles:\n"
      "  - {id: 1.5, start: [0, 0, 0]}\n"
      "  - {id: 2, start: [0, 0, 50]}\n"
      "  - {id: 3, start: [1, 1, 0], speed: 3}\n"
      "  - {id: 3, start: [4, 1, 0]}\n");
  EXPECT_PRED2(says, many, "fleet.yaml:vehicles[0].id: 1.5: expected a whole number");
  EXPECT_PRED2(says, many, "fleet.yaml:vehicles[1].start: [0, 0, 50]: outside the world's bounds");
  EXPECT_PRED2(says, many, "fleet.yaml:vehicles[2].speed: 3: unknown key");
  EXPECT_PRED2(says, many, "fleet.yaml:vehicles[3].id: 3: already the id of vehicles[2]");
  std::string crowd = "vehicles:\n";
  for (int id = 1; id <= common::kMaxFleetVehicles + 1; ++id) {
    crowd += "  - {id: " + std::to_string(id) + ", start: [" + std::to_string(id % 10) + ", " + std::to_string(id / 10) + ", 0]}\n";
  }
  EXPECT_PRED2(says, fleetRefusal(crowd), "fleet.yaml:vehicles: 65 vehicles: at most 64 fly in one domain");
}

}  // namespace
}  // namespace quad::plant
