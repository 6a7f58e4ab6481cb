// SPDX-License-Identifier: BSD-3-Clause
#include "quad/vehicle/vehicle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace quad::vehicle {
namespace {

TEST(Vehicle, ShippedVehiclesLoad)
{
  for (const char* name : {"x500", "lee2010"}) {
    const VehicleParams v = loadVehicle(std::string(QUAD_CONFIG_DIR) + "/vehicles/" + name + ".yaml");
    EXPECT_GT(v.mass, 0.0) << name;
    EXPECT_GT(v.rotor_speed_max, v.hoverRotorSpeed()) << name;
  }
}

TEST(Vehicle, AllocationSignsFollowTheLayout)
{
  VehicleParams v;
  const Eigen::Matrix4d A = v.allocation();
  // Front-left rotor: lifts, rolls right (+x torque lifts the left side), pitches nose up
  // (−y torque), and as a counter-clockwise rotor yaws the body clockwise (−z).
  EXPECT_GT(A(0, 0), 0.0);
  EXPECT_GT(A(1, 0), 0.0);
  EXPECT_LT(A(2, 0), 0.0);
  EXPECT_LT(A(3, 0), 0.0);
  // Rear-right: rolls left, pitches nose down, also counter-clockwise.
  EXPECT_LT(A(1, 2), 0.0);
  EXPECT_GT(A(2, 2), 0.0);
  EXPECT_LT(A(3, 2), 0.0);
  // Equal speeds: pure thrust.
  const Eigen::Vector4d w2 = Eigen::Vector4d::Constant(100.0 * 100.0);
  const Eigen::Vector4d wrench = A * w2;
  EXPECT_NEAR(wrench[1], 0.0, 1e-12);
  EXPECT_NEAR(wrench[2], 0.0, 1e-12);
  EXPECT_NEAR(wrench[3], 0.0, 1e-12);
  // Invertible: a mixer can solve it.
  EXPECT_GT(std::abs(A.determinant()), 0.0);
}

TEST(Vehicle, HoverSpeedCarriesTheWeight)
{
  VehicleParams v;
  const double w = v.hoverRotorSpeed(9.81);
  EXPECT_NEAR(4.0 * v.thrust_coefficient * w * w, v.mass * 9.81, 1e-9);
}

TEST(Vehicle, ContradictoryValuesAreRefusedNamingTheKey)
{
  const auto schema = vehicleSchema();
  const std::string base =
      "mass: 2\ninertia: [0.02, 0.02, 0.04]\narm_length: 0.25\nradius: 0.3\n"
      "rotor: {thrust_coefficient: 8.5e-6, torque_coefficient: 1.4e-7, ";
  try {
    vehicleFromParams(common::parseParams(base + "speed_max: 100}", "v.yaml", schema));
    FAIL();
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("v.yaml:rotor.speed_max: 100: full thrust"), std::string::npos)
        << e.what();
  }
  try {
    vehicleFromParams(common::parseParams(base + "speed_min: 500, speed_max: 400}", "v.yaml", schema));
    FAIL();
  } catch (const common::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("v.yaml:rotor.speed_min: 500: must be below"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(common::parseParams("mass: .nan", "v.yaml", schema), common::ConfigError);
}

}  // namespace
}  // namespace quad::vehicle
