// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/mixer.hpp"

#include <gtest/gtest.h>

#include "closed_loop.hpp"

namespace quad::control {
namespace {

TEST(Mixer, InsideTheLimitsItDeliversExactlyWhatWasAsked)
{
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const MixerOutput out = mixer.mix(v.mass * 9.81, Vector3(0.2, -0.1, 0.02));
  EXPECT_FALSE(out.saturated);
  EXPECT_NEAR(out.thrust, v.mass * 9.81, 1e-9);
  EXPECT_NEAR((out.torque_B - Vector3(0.2, -0.1, 0.02)).norm(), 0.0, 1e-9);
}

TEST(Mixer, YawGivesWayBeforeRollAndPitch)
{
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const MixerOutput out = mixer.mix(v.mass * 9.81, Vector3(1.5, 0.0, 1.0));  // far too much yaw
  EXPECT_TRUE(out.saturated);
  EXPECT_DOUBLE_EQ(out.roll_pitch_scale, 1.0);
  EXPECT_LT(out.yaw_scale, 1.0);
  EXPECT_NEAR(out.torque_B.x(), 1.5, 1e-6);
  EXPECT_LT(out.torque_B.z(), 1.0);
}

TEST(Mixer, ThrustGivesWayToKeepTheTorques)
{
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const double max_thrust = 4 * v.thrust_coefficient * v.rotor_speed_max * v.rotor_speed_max;
  const MixerOutput out = mixer.mix(max_thrust, Vector3(0.5, 0.3, 0.0));
  EXPECT_TRUE(out.thrust_limited);
  EXPECT_DOUBLE_EQ(out.roll_pitch_scale, 1.0);
  EXPECT_NEAR(out.torque_B.x(), 0.5, 1e-6);
  EXPECT_LT(out.thrust, max_thrust);
}

TEST(Mixer, YawGivesWayBeforeThrust)
{
  // A climb at 1.6 g with a yaw demand beyond what the rotors can add on top of it: the
  // thrust is delivered, the yaw is what is left.
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const double thrust = 1.6 * v.mass * 9.81;
  const MixerOutput out = mixer.mix(thrust, Vector3(0.1, 0.0, 0.5));
  EXPECT_TRUE(out.saturated);
  EXPECT_FALSE(out.thrust_limited);
  EXPECT_NEAR(out.thrust, thrust, 1e-6);
  EXPECT_NEAR(out.torque_B.x(), 0.1, 1e-6);
  EXPECT_GT(out.yaw_scale, 0.0);
  EXPECT_LT(out.yaw_scale, 1.0);
  EXPECT_NEAR(out.torque_B.z(), out.yaw_scale * 0.5, 1e-6);
  for (const double w : out.rotor_speed) {
    EXPECT_LE(w, v.rotor_speed_max);
  }
}

TEST(Mixer, ImpossibleRollIsScaledAndReported)
{
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const MixerOutput out = mixer.mix(v.mass * 9.81, Vector3(50.0, 0.0, 0.0));
  EXPECT_TRUE(out.saturated);
  EXPECT_LT(out.roll_pitch_scale, 1.0);
  EXPECT_GT(out.torque_B.x(), 0.0);
  for (const double w : out.rotor_speed) {
    EXPECT_GE(w, v.rotor_speed_min);
    EXPECT_LE(w, v.rotor_speed_max);
  }
}

TEST(Mixer, NonFiniteRequestsGiveHoverThrustFlagged)
{
  const vehicle::VehicleParams v = test::loadVehicle("x500");
  const Mixer mixer(v);
  const MixerOutput out = mixer.mix(NAN, Vector3(0, INFINITY, 0));
  EXPECT_TRUE(out.saturated);
  EXPECT_NEAR(out.thrust, v.mass * 9.81, 1e-9);
  EXPECT_NEAR(out.torque_B.norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace quad::control
