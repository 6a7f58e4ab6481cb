// SPDX-License-Identifier: BSD-3-Clause
// Physics of the plant core: each test states a law the simulation must obey.
#include "quad/plant/dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace quad::plant {
namespace {

vehicle::VehicleParams dragFree()
{
  vehicle::VehicleParams v;
  v.mass = 2.0;
  v.inertia = {0.02, 0.03, 0.045};
  v.drag_linear.setZero();
  v.drag_quadratic.setZero();
  return v;
}

RotorArray all(double w) { return {w, w, w, w}; }

TEST(Dynamics, FreeFallMatchesHalfGTSquared)
{
  // GIVEN a vehicle at 100 m with its rotors stopped and no drag
  const QuadrotorDynamics dyn(dragFree());
  RigidBodyState s;
  s.p_W = {1.0, 2.0, 100.0};
  const Environment env;
  // WHEN it falls for 3 s
  const double dt = 1e-3;
  for (int k = 0; k < 3000; ++k) {
    dyn.step(s, all(0.0), env, dt);
  }
  // THEN z = 100 − g t²/2 and v = −g t (RK4 is exact on a constant acceleration)
  EXPECT_NEAR(s.p_W.z(), 100.0 - 0.5 * 9.81 * 9.0, 1e-9);
  EXPECT_NEAR(s.v_W.z(), -9.81 * 3.0, 1e-9);
  EXPECT_NEAR(s.p_W.x(), 1.0, 1e-12);
}

TEST(Dynamics, APushAddsItsImpulseOverTheMass)
{
  // GIVEN a drag-free vehicle falling from rest, once alone and once pushed sideways and up
  const QuadrotorDynamics dyn(dragFree());
  RigidBodyState alone;
  alone.p_W = {0.0, 0.0, 100.0};
  RigidBodyState pushed = alone;
  Environment push;
  push.force_W = {0.0, 6.0, 4.0};  // [N]
  // WHEN the push lasts 0.5 s
  const double dt = 1e-3;
  for (int k = 0; k < 500; ++k) {
    dyn.step(alone, all(0.0), Environment{}, dt);
    dyn.step(pushed, all(0.0), push, dt);
  }
  // THEN the velocities differ by F t / m and the positions by F t² / 2m (m = 2 kg)
  const Vector3 dv = pushed.v_W - alone.v_W;
  const Vector3 dp = pushed.p_W - alone.p_W;
  EXPECT_NEAR(dv.y(), 6.0 * 0.5 / 2.0, 1e-9);
  EXPECT_NEAR(dv.z(), 4.0 * 0.5 / 2.0, 1e-9);
  EXPECT_NEAR(dp.y(), 6.0 * 0.25 / 4.0, 1e-9);
  EXPECT_NEAR(dv.x(), 0.0, 1e-12);
}

TEST(Dynamics, HoverNeedsTotalThrustMGAndStaysPut)
{
  const QuadrotorDynamics dyn(dragFree());
  const double hover = dyn.params().hoverRotorSpeed(9.81);
  RigidBodyState s;
  s.p_W = {0.0, 0.0, 5.0};
  s.rotor_speed = all(hover);
  const Environment env;
  EXPECT_NEAR(dyn.wrench(s, env).force_B.z(), dyn.params().mass * 9.81, 1e-9);
  for (int k = 0; k < 10000; ++k) {
    dyn.step(s, all(hover), env, 1e-3);
  }
  EXPECT_LT((s.p_W - Vector3(0, 0, 5)).norm(), 1e-9);
  EXPECT_LT(s.w_B.norm(), 1e-12);
}

struct SpinErrors {
  double momentum;
  double energy;
};

SpinErrors torqueFreeSpin(double dt)
{
  QuadrotorDynamics dyn(dragFree());
  RigidBodyState s;
  s.p_W.z() = 100.0;         // in the air: no ground contact
  s.w_B = {2.0, -1.0, 3.0};  // not about a principal axis: the body tumbles
  Environment env;
  env.gravity_W.setZero();
  const Vector3 L0 = dyn.angularMomentum_W(s);
  const double E0 = dyn.kineticEnergy(s);
  const int steps = static_cast<int>(std::lround(2.0 / dt));
  for (int k = 0; k < steps; ++k) {
    dyn.step(s, all(0.0), env, dt);
  }
  return {(dyn.angularMomentum_W(s) - L0).norm(), std::abs(dyn.kineticEnergy(s) - E0)};
}

TEST(Dynamics, TorqueFreeSpinConservesMomentumAndEnergyWithinRk4Error)
{
  const SpinErrors coarse = torqueFreeSpin(4e-3);
  const SpinErrors fine = torqueFreeSpin(2e-3);
  EXPECT_LT(coarse.momentum, 1e-6);
  EXPECT_LT(coarse.energy, 1e-6);
  // Fourth order: halving the step shrinks the error ~16× (12× to 20× allowed).
  EXPECT_GT(coarse.momentum / fine.momentum, 12.0);
  EXPECT_LT(coarse.momentum / fine.momentum, 20.0);
  EXPECT_GT(coarse.energy / fine.energy, 12.0);
  EXPECT_LT(coarse.energy / fine.energy, 20.0);
}

TEST(Dynamics, CounterClockwisePairYawsTheBodyClockwise)
{
  const QuadrotorDynamics dyn(dragFree());
  const double hover = dyn.params().hoverRotorSpeed(9.81);
  RigidBodyState s;
  s.p_W = {0.0, 0.0, 10.0};
  // Rotors 0 and 2 (counter-clockwise) faster, 1 and 3 slower: same thrust, net reaction.
  const RotorArray cmd{hover * 1.05, hover * 0.95, hover * 1.05, hover * 0.95};
  s.rotor_speed = cmd;
  const Wrench w = dyn.wrench(s, {});
  EXPECT_LT(w.torque_B.z(), 0.0);
  EXPECT_NEAR(w.torque_B.x(), 0.0, 1e-12);
  EXPECT_NEAR(w.torque_B.y(), 0.0, 1e-12);
  for (int k = 0; k < 500; ++k) {
    dyn.step(s, cmd, {}, 1e-3);
  }
  EXPECT_LT(s.w_B.z(), 0.0);
  EXPECT_LT(geometry::yprFromMatrix(geometry::toMatrix(s.q_WB)).yaw, 0.0);
}

TEST(Dynamics, FrontRotorsLiftTheNose)
{
  const QuadrotorDynamics dyn(dragFree());
  const double hover = dyn.params().hoverRotorSpeed(9.81);
  RigidBodyState s;
  s.p_W.z() = 10.0;
  s.rotor_speed = {hover * 1.02, hover, hover, hover * 1.02};  // front-left, front-right
  const Wrench w = dyn.wrench(s, {});
  EXPECT_LT(w.torque_B.y(), 0.0);  // −y torque: nose up in FLU
}

TEST(Dynamics, MotorsFollowWithTheirTimeConstants)
{
  vehicle::VehicleParams v = dragFree();
  v.motor_time_constant_up = 0.02;
  v.motor_time_constant_down = 0.05;
  const QuadrotorDynamics dyn(v);
  RigidBodyState s;
  s.p_W.z() = 1000.0;
  for (int k = 0; k < 20; ++k) {  // one up time constant
    dyn.step(s, all(500.0), {}, 1e-3);
  }
  EXPECT_NEAR(s.rotor_speed[0], 500.0 * (1.0 - std::exp(-1.0)), 1e-4);
  for (int k = 0; k < 2000; ++k) {
    dyn.step(s, all(500.0), {}, 1e-3);
  }
  for (int k = 0; k < 50; ++k) {  // one down time constant
    dyn.step(s, all(0.0), {}, 1e-3);
  }
  EXPECT_NEAR(s.rotor_speed[0], 500.0 * std::exp(-1.0), 1e-3);
  // Commands beyond the limits are clamped.
  for (int k = 0; k < 2000; ++k) {
    dyn.step(s, all(1e9), {}, 1e-3);
  }
  EXPECT_LE(s.rotor_speed[0], v.rotor_speed_max);
}

TEST(Dynamics, GroundStopsTheVehicleWithoutTunnelling)
{
  const QuadrotorDynamics dyn(dragFree());
  RigidBodyState s;
  s.p_W = {0.0, 0.0, 0.5};
  s.v_W = {1.0, 0.0, -40.0};  // 4 cm per 1 ms step
  s.w_B = {0.5, 0.2, 0.1};
  for (int k = 0; k < 100; ++k) {
    dyn.step(s, all(0.0), {}, 1e-3);
    EXPECT_GE(s.p_W.z(), 0.0);
  }
  EXPECT_TRUE(s.landed);
  EXPECT_EQ(s.v_W, Vector3::Zero());
  EXPECT_EQ(s.p_W.z(), 0.0);
  const auto ypr = geometry::yprFromMatrix(geometry::toMatrix(s.q_WB));
  EXPECT_NEAR(ypr.roll, 0.0, 1e-12);
  EXPECT_NEAR(ypr.pitch, 0.0, 1e-12);
}

TEST(Dynamics, LandedVehicleTakesOffOnlyWhenThrustBeatsWeight)
{
  const QuadrotorDynamics dyn(dragFree());
  const double hover = dyn.params().hoverRotorSpeed(9.81);
  RigidBodyState s;
  s.landed = true;
  for (int k = 0; k < 500; ++k) {
    dyn.step(s, all(0.95 * hover), {}, 1e-3);
  }
  EXPECT_TRUE(s.landed);
  EXPECT_EQ(s.p_W.z(), 0.0);
  for (int k = 0; k < 1000; ++k) {
    dyn.step(s, all(1.1 * hover), {}, 1e-3);
  }
  EXPECT_FALSE(s.landed);
  EXPECT_GT(s.p_W.z(), 0.1);
}

TEST(Dynamics, QuaternionStaysUnitAndDragOpposesMotion)
{
  vehicle::VehicleParams v = dragFree();
  v.drag_linear = {0.5, 0.5, 0.5};
  const QuadrotorDynamics dyn(v);
  RigidBodyState s;
  s.p_W.z() = 100.0;
  s.v_W = {10.0, 0.0, 0.0};
  s.w_B = {3.0, -2.0, 5.0};
  Environment env;
  env.gravity_W.setZero();
  for (int k = 0; k < 5000; ++k) {
    dyn.step(s, all(0.0), env, 1e-3);
    ASSERT_NEAR(s.q_WB.norm(), 1.0, 1e-12);
  }
  // Linear drag alone: v = v0 e^{−c t / m}.
  EXPECT_NEAR(s.v_W.norm(), 10.0 * std::exp(-0.5 * 5.0 / v.mass), 1e-6);
  // Wind is relative motion: a vehicle at rest in a 5 m/s wind is pushed downwind.
  RigidBodyState still;
  still.p_W.z() = 10.0;
  env.wind_W = {5.0, 0.0, 0.0};
  EXPECT_GT(dyn.wrench(still, env).force_B.x(), 0.0);
}

TEST(Dynamics, FailedRotorLosesItsThrust)
{
  const QuadrotorDynamics dyn(dragFree());
  const double hover = dyn.params().hoverRotorSpeed(9.81);
  RigidBodyState s;
  s.rotor_speed = all(hover);
  Environment env;
  env.rotor_efficiency = {0.0, 1.0, 1.0, 1.0};
  const Wrench w = dyn.wrench(s, env);
  EXPECT_NEAR(w.force_B.z(), 0.75 * dyn.params().mass * 9.81, 1e-9);
  EXPECT_LT(w.torque_B.x(), 0.0);  // the left side lost lift: rolls left
}

}  // namespace
}  // namespace quad::plant
