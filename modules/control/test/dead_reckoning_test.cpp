// SPDX-License-Identifier: BSD-3-Clause
// Dead reckoning against motions whose IMU readings and states are known in closed form.
#include "quad/control/dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "quad/geometry/quaternion.hpp"
#include "quad/geometry/distance.hpp"

namespace quad::control {
namespace {

constexpr double kG = 9.81;

/// Spinning about world z at `yaw_rate` while accelerating at a constant `a_W`.
struct SpinningAcceleration {
  Vector3 p0{1.0, -2.0, 3.0};
  Vector3 v0{2.0, 0.5, -0.2};
  Vector3 a_W{0.8, -0.3, 0.4};
  double yaw_rate = 0.7;

  Quaternion q(double t) const { return geometry::fromAxisAngle(Vector3::UnitZ(), yaw_rate * t); }
  VehicleState state(double t) const
  {
    return {p0 + v0 * t + 0.5 * a_W * t * t, v0 + a_W * t, q(t), Vector3(0.0, 0.0, yaw_rate)};
  }
  InertialSample imu(double t) const
  {
    return {geometry::rotate(q(t).conjugate(), a_W + Vector3(0.0, 0.0, kG)), Vector3(0.0, 0.0, yaw_rate)};
  }
};

TEST(DeadReckoning, CarriesTheStateOnAlongAKnownMotion)
{
  // GIVEN the state at t = 0 and ideal IMU samples at 250 Hz for 2 s
  const SpinningAcceleration m;
  DeadReckoning dr(kG);
  dr.anchor(m.state(0.0), 0.0);
  for (int k = 1; k <= 500; ++k) {
    const double t = 0.004 * k;
    // each sample held over the interval before it: the sample at the interval's start
    ASSERT_TRUE(dr.onImu(m.imu(t - 0.004), t));
  }
  // THEN the estimate agrees with the motion (exact for a constant acceleration and rate,
  // to the rounding)
  const auto e = dr.estimate(2.0, 0.1, 2.0);
  ASSERT_TRUE(e.has_value());
  const VehicleState truth = m.state(2.0);
  EXPECT_LT((e->p_W - truth.p_W).norm(), 1e-9);
  EXPECT_LT((e->v_W - truth.v_W).norm(), 1e-9);
  EXPECT_LT(geometry::geodesicAngle(e->q_WB, truth.q_WB), 1e-9);
  EXPECT_DOUBLE_EQ(dr.time(), 2.0);
}

TEST(DeadReckoning, AtRestStaysPut)
{
  // The specific force at rest is +g along body z: it must cancel gravity exactly
  DeadReckoning dr(kG);
  const VehicleState rest{Vector3(4, 5, 0), Vector3::Zero(), Quaternion::identity(), Vector3::Zero()};
  dr.anchor(rest, 10.0);
  for (int k = 1; k <= 250; ++k) {
    ASSERT_TRUE(dr.onImu({Vector3(0, 0, kG), Vector3::Zero()}, 10.0 + 0.004 * k));
  }
  const auto e = dr.estimate(11.0, 0.1, 2.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_LT((e->p_W - rest.p_W).norm(), 1e-12);
  EXPECT_LT(e->v_W.norm(), 1e-12);
}

TEST(DeadReckoning, GivesNoEstimateWithoutAnAnchorPastItsHorizonOrAfterAnImuGap)
{
  DeadReckoning dr(kG);
  EXPECT_FALSE(dr.estimate(0.0, 0.1, 2.0).has_value());  // nothing to carry
  EXPECT_TRUE(dr.onImu({Vector3(0, 0, kG), Vector3::Zero()}, 0.5));  // taken, nothing to apply
  EXPECT_LT(dr.time(), 0.0);
  const VehicleState s{Vector3::Zero(), Vector3::Zero(), Quaternion::identity(), Vector3::Zero()};
  dr.anchor(s, 1.0);
  EXPECT_TRUE(dr.estimate(1.05, 0.1, 2.0).has_value());  // the anchor itself, young enough
  EXPECT_FALSE(dr.estimate(1.2, 0.1, 2.0).has_value());  // no IMU sample for 0.2 s
  for (int k = 1; k <= 600; ++k) {
    dr.onImu({Vector3(0, 0, kG), Vector3::Zero()}, 1.0 + 0.004 * k);
  }
  EXPECT_TRUE(dr.estimate(3.0, 0.1, 2.0).has_value());
  EXPECT_FALSE(dr.estimate(3.4, 0.1, 2.0).has_value());  // 2.4 s after the anchor
  // A sample at or before the estimate's time changes nothing.
  const double t = dr.time();
  EXPECT_TRUE(dr.onImu({Vector3(100, 0, 0), Vector3::Zero()}, t));
  EXPECT_EQ(dr.time(), t);
  EXPECT_LT(dr.estimate(t, 0.1, 10.0)->v_W.norm(), 1e-12);
}

TEST(DeadReckoning, RefusesNonFiniteSamplesAndChangesNothing)
{
  DeadReckoning dr(kG);
  const VehicleState s{Vector3::Zero(), Vector3::Zero(), Quaternion::identity(), Vector3::Zero()};
  dr.anchor(s, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(dr.onImu({Vector3(nan, 0, 0), Vector3::Zero()}, 0.004));
  EXPECT_FALSE(dr.onImu({Vector3::Zero(), Vector3(0, INFINITY, 0)}, 0.004));
  EXPECT_FALSE(dr.onImu({Vector3::Zero(), Vector3(1e308, 1e308, 0)}, 0.004));  // |ω| overflows
  EXPECT_FALSE(dr.onImu({Vector3(0, 0, kG), Vector3::Zero()}, nan));
  EXPECT_EQ(dr.time(), 0.0);
  EXPECT_TRUE(dr.onImu({Vector3(0, 0, kG), Vector3::Zero()}, 0.004));
  EXPECT_EQ(dr.estimate(0.004, 0.1, 2.0)->p_W, Vector3::Zero());
}

}  // namespace
}  // namespace quad::control
