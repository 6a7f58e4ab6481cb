// SPDX-License-Identifier: BSD-3-Clause
// The filter against closed-form motions flown past the plant's sensor models, fixed seeds.
#include "quad/estimation/error_state_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <Eigen/Cholesky>

#include "flight.hpp"

namespace quad::estimation {
namespace {

using test::Truth;

struct Errors {
  double p_rms = 0.0;
  double p_max = 0.0;
  double yaw_rms = 0.0;  ///< [rad]
  double v_rms = 0.0;
  int n = 0;
  void add(const Truth& x, const Estimate& e)
  {
    const double dp = (e.p_W - x.p_W).norm();
    p_rms += dp * dp;
    p_max = std::max(p_max, dp);
    v_rms += (e.v_W - x.v_W).squaredNorm();
    const double dyaw = test::attitudeError(x, e).z();
    yaw_rms += dyaw * dyaw;
    ++n;
  }
  void finish()
  {
    p_rms = std::sqrt(p_rms / n);
    v_rms = std::sqrt(v_rms / n);
    yaw_rms = std::sqrt(yaw_rms / n);
  }
};

EstimatorParams movingStart()
{
  EstimatorParams p;
  // Aligned in motion: the zero velocity it starts with is that far off, and the
  // accelerometer reads more than gravity (3 m/s in a 10 m circle: 0.09 rad of false tilt).
  p.initial_velocity_std = 3.0;
  p.initial_tilt_std = 0.15;
  p.initial_yaw_std = 0.3;
  return p;
}

Errors flyAndScore(ErrorStateFilter& filter, const test::Motion& motion, double seconds, test::Sensors sensors,
                   std::uint64_t seed, double settle_s)
{
  Errors errors;
  test::fly(filter, motion, seconds, sensors, seed, [&](double t, const Truth& x) {
    if (t >= settle_s) {
      errors.add(x, filter.estimate(static_cast<std::int64_t>(t * 1e9)));
    }
  });
  errors.finish();
  return errors;
}

// GIVEN a vehicle flying a straight line at 2 m/s WHEN the filter fuses the default sensors
// THEN after it settles the position is within the goal's 5 cm RMS, the velocity within
// 5 cm/s and the yaw within 1°, and it reports itself healthy and aided.
TEST(ErrorStateFilter, AConstantVelocityLineIsTrackedWithinTheGoals)
{
  ErrorStateFilter filter(movingStart());
  const auto e = flyAndScore(filter, test::constantVelocity({0, 0, 2}, {2.0, 0.5, 0.1}, 0.3), 60.0, {}, 1, 10.0);
  EXPECT_LT(e.p_rms, 0.05);
  EXPECT_LT(e.v_rms, 0.05);
  EXPECT_LT(e.yaw_rms, 1.0 * M_PI / 180);
  const Health h = filter.health(60'000'000'000);
  EXPECT_TRUE(h.ok());
  EXPECT_TRUE(h.position_aided);
  EXPECT_TRUE(h.heading_aided);
  EXPECT_EQ(filter.positionCounts().bad, 0U);
}

// GIVEN a vehicle falling from rest for half a second (a start in the air: the accelerometer
// reads its noise alone), then braking on its rotors WHEN the filter aligns in the fall THEN
// it takes itself for moving (level, with a wide 1σ) and tracks the fall and the braking;
// aligned as if at rest, its tilt would be the noise's direction, flown as sure.
TEST(ErrorStateFilter, AnAlignmentInAFallIsTakenForMovingAndTracksTheBraking)
{
  static constexpr double g = 9.81;
  static constexpr double t_brake = 0.5;
  static constexpr double a_up = 0.5 * g;  // net, while braking
  const test::Motion fall = [](double t) {
    Truth x;
    const double tf = std::min(t, t_brake);
    const double tb = std::max(0.0, t - t_brake);
    x.p_W = Vector3(0.0, 0.0, 50.0 - 0.5 * g * tf * tf - g * t_brake * tb + 0.5 * a_up * tb * tb);
    x.v_W = Vector3(0.0, 0.0, -g * tf + a_up * tb);
    x.a_W = Vector3(0.0, 0.0, t < t_brake ? -g : a_up);
    return x;
  };
  for (const bool assume_rest : {false, true}) {
    EstimatorParams params;
    if (assume_rest) {
      params.rest_tolerance = 100.0;  // any accelerometer reading counts as at rest, at once
      params.rest_speed = 1e3;
      params.rest_window = 0.0;
    }
    ErrorStateFilter filter(params);
    // The worst tilt while the rotors take over (the first half second of braking): what a
    // controller catching the fall would fly on; then the errors once braking.
    double worst_tilt = 0.0;
    Errors e;
    test::fly(filter, fall, 3.0, {}, 3, [&](double t, const Truth& x) {
      const Estimate now = filter.estimate(static_cast<std::int64_t>(t * 1e9));
      if (t >= t_brake && t < t_brake + 0.5 && filter.aligned()) {
        worst_tilt = std::max(worst_tilt, test::attitudeError(x, now).head<2>().norm());
      } else if (t >= 1.5) {
        e.add(x, now);
      }
    });
    e.finish();
    if (assume_rest) {
      EXPECT_GT(worst_tilt, 0.5) << "the noise's direction, flown as sure";
      continue;
    }
    // (0.04 with the heading's 1σ left narrow: widened as the unknown tilt makes it, 0.085)
    EXPECT_LT(worst_tilt, 0.1);
    EXPECT_LT(e.p_rms, 0.05);
    EXPECT_LT(e.v_rms, 0.1);
    EXPECT_EQ(filter.positionCounts().rejected, 0U);
  }
}

// GIVEN an estimator started while the vehicle brakes from 3 m/s at 2 m/s² (a restart in
// flight: pitched back 0.2 rad, the accelerometer reads gravity's magnitude within 0.2 m/s²
// and the gyroscope nothing), pitches level in 0.2 s and holds still WHEN it aligns THEN it waits through the braking, whose fixes move, and
// aligns once the vehicle has been still for the rest window, with the tilt within its
// at-rest 1σ and the heading within 3°. Not waiting, it would fly the 0.2 rad of pitch as
// level, sure of it (its 1σ 0.02 rad).
TEST(ErrorStateFilter, AnEstimatorStartedWhileBrakingAlignsOnceTheVehicleIsStill)
{
  static constexpr double g = 9.81;
  static constexpr double decel = 2.0;
  static constexpr double t_stop = 1.5;
  static constexpr double t_level = 0.2;  // to pitch back level
  const double pitch = std::atan2(-decel, g);
  const test::Motion braking = [pitch](double t) {
    Truth x;
    const double tb = std::min(t, t_stop);
    const double levelling = std::clamp((t - t_stop) / t_level, 0.0, 1.0);
    x.p_W = Vector3(3.0 * tb - 0.5 * decel * tb * tb, 0.0, 3.0);
    x.v_W = Vector3(3.0 - decel * tb, 0.0, 0.0);
    x.a_W = Vector3(t < t_stop ? -decel : 0.0, 0.0, 0.0);
    x.R_WB = geometry::rotY(pitch * (1.0 - levelling));
    x.w_B = Vector3(0.0, levelling > 0.0 && levelling < 1.0 ? -pitch / t_level : 0.0, 0.0);
    return x;
  };
  for (const bool assume_rest : {false, true}) {
    EstimatorParams params;
    if (assume_rest) {
      params.rest_speed = 1e3;
    }
    ErrorStateFilter filter(params);
    double aligned_at = -1.0;
    double tilt_error = 0.0;  // the worst in the first half second aligned
    double yaw_error = 0.0;
    test::fly(filter, braking, 3.0, {}, 11, [&](double t, const Truth& x) {
      if (!filter.aligned()) {
        return;
      }
      aligned_at = aligned_at < 0.0 ? t : aligned_at;
      if (t < aligned_at + 0.5) {
        const Estimate now = filter.estimate(static_cast<std::int64_t>(t * 1e9));
        const Vector3 e = test::attitudeError(x, now);
        tilt_error = std::max(tilt_error, e.head<2>().norm());
        yaw_error = std::max(yaw_error, std::abs(e.z()));
      }
    });
    ASSERT_GT(aligned_at, 0.0);
    if (assume_rest) {
      EXPECT_LT(aligned_at, t_stop);
      EXPECT_GT(tilt_error, 0.1) << "the braking's pitch, flown as level";
      continue;
    }
    EXPECT_GE(aligned_at, t_stop + t_level + params.rest_window);
    EXPECT_LT(aligned_at, t_stop + t_level + params.rest_window + 0.3);
    EXPECT_LT(tilt_error, 2.0 * params.initial_tilt_std);
    EXPECT_LT(yaw_error, 3.0 * M_PI / 180);
    EXPECT_EQ(filter.positionCounts().rejected, 0U);
  }
}

// GIVEN a vehicle that never comes to rest (a straight line at 2 m/s) WHEN the filter waits
// for rest THEN it aligns as moving after initial.moving_after, not before, and tracks the
// line within the goals once settled.
TEST(ErrorStateFilter, AVehicleNeverAtRestIsAlignedAsMovingAfterTheWait)
{
  const EstimatorParams params;
  ErrorStateFilter filter(params);
  double aligned_at = -1.0;
  Errors e;
  test::fly(filter, test::constantVelocity({0, 0, 2}, {2.0, 0.5, 0.1}, 0.3), 20.0, {}, 4,
            [&](double t, const Truth& x) {
              if (filter.aligned() && aligned_at < 0.0) {
                aligned_at = t;
              }
              if (t >= 10.0) {
                e.add(x, filter.estimate(static_cast<std::int64_t>(t * 1e9)));
              }
            });
  e.finish();
  EXPECT_GE(aligned_at, params.moving_after);
  EXPECT_LT(aligned_at, params.moving_after + 0.3);
  EXPECT_LT(e.p_rms, 0.05);
  EXPECT_LT(e.yaw_rms, 1.0 * M_PI / 180);
}

// GIVEN a level circle of 10 m radius at 3 m/s (a constant turn rate and a centripetal
// acceleration the IMU measures) WHEN fused THEN the same bounds hold.
TEST(ErrorStateFilter, ACoordinatedTurnIsTrackedWithinTheGoals)
{
  ErrorStateFilter filter(movingStart());
  const auto e = flyAndScore(filter, test::coordinatedTurn({0, 0, 3}, 10.0, 3.0), 60.0, {}, 2, 10.0);
  EXPECT_LT(e.p_rms, 0.05);
  EXPECT_LT(e.v_rms, 0.08);
  EXPECT_LT(e.yaw_rms, 1.0 * M_PI / 180);
}

// GIVEN a hover with IMU biases far from zero WHEN fused THEN the gyroscope's biases are
// learnt (roll and pitch rates against gravity, yaw rate against the magnetometer), and the
// vertical accelerometer bias against the fixes; the horizontal accelerometer biases trade
// off against tilt in a level hover (unobservable apart), but the specific force the
// estimate predicts matches what the accelerometer reads.
TEST(ErrorStateFilter, AHoverWithBiasesLearnsThemAsFarAsTheyAreObservable)
{
  ErrorStateFilter filter(EstimatorParams{});
  test::Sensors sensors;
  sensors.bias.accel = {0.08, -0.06, 0.15};
  sensors.bias.gyro = {0.01, -0.008, 0.006};
  const auto e = flyAndScore(filter, test::constantVelocity({1, 2, 1.5}, Vector3::Zero(), -0.7), 120.0, sensors, 3, 20.0);
  const Estimate est = filter.estimate(120'000'000'000);
  EXPECT_LT((est.gyro_bias_B - sensors.bias.gyro).norm(), 0.0015);
  EXPECT_NEAR(est.accel_bias_B.z(), 0.15, 0.02);
  // Tilt and horizontal bias together: R̂ᵀ(−g) + b̂ ≈ the reading's mean, Rᵀ(−g) + b.
  const Matrix3 R_hat = geometry::toMatrix(est.q_WB);
  const Vector3 predicted = R_hat.transpose() * Vector3(0, 0, 9.81) + est.accel_bias_B;
  const Vector3 read = geometry::rotZ(-0.7).transpose() * Vector3(0, 0, 9.81) + sensors.bias.accel;
  EXPECT_LT((predicted - read).norm(), 0.01);
  EXPECT_LT(e.p_rms, 0.03);
  EXPECT_LT(e.yaw_rms, 1.0 * M_PI / 180);
}

// GIVEN 20 seeded runs of a turn entered from rest, with IMU biases drawn at turn-on and
// walking, WHEN the position's and the attitude's normalised
// estimation error squared (NEES, eᵀP⁻¹e) are averaged over the runs at 20 times THEN the
// averages lie in the two-sided 95 % χ² band of 3·20 degrees of freedom, /20, at 18 of the
// 20 times or more (one in twenty falls outside by chance), and their mean over the times is
// within 20 % of the 3 of a consistent filter: the covariance it reports is the error it
// makes.
TEST(ErrorStateFilter, TheNeesStaysInItsChiSquareBand)
{
  constexpr std::uint64_t kRuns = 20;
  constexpr std::size_t kTimes = 20;
  std::array<double, kTimes> p_nees{};
  std::array<double, kTimes> att_nees{};
  for (std::uint64_t run = 0; run < kRuns; ++run) {
    test::Sensors sensors;
    sensors.walk = true;
    std::mt19937_64 draw(100 + run);
    sensors.bias = plant::turnOnBias(sensors.imu, draw);
    ErrorStateFilter filter(EstimatorParams{});
    std::size_t k = 0;
    test::fly(filter, test::spinUpTurn({0, 0, 3}, 10.0, 3.0, 5.0), 60.0, sensors, 100 + run, [&](double t, const Truth& x) {
      const double at = 20.0 + 2.0 * static_cast<double>(k);
      if (k < kTimes && t >= at - 1e-9) {
        const Estimate e = filter.estimate(static_cast<std::int64_t>(t * 1e9));
        const Vector3 dp = x.p_W - e.p_W;
        const Matrix3 Pp = filter.covariance().block<3, 3>(kPosition, kPosition);
        p_nees[k] += dp.dot(Pp.ldlt().solve(dp)) / static_cast<double>(kRuns);
        const Vector3 dth = test::attitudeError(x, e);
        const Matrix3 Pa = filter.covariance().block<3, 3>(kAttitude, kAttitude);
        att_nees[k] += dth.dot(Pa.ldlt().solve(dth)) / static_cast<double>(kRuns);
        ++k;
      }
    });
  }
  // χ²(60) quantiles 2.5 % and 97.5 %: 40.48 and 83.30.
  const double lo = 40.48 / static_cast<double>(kRuns);
  const double hi = 83.30 / static_cast<double>(kRuns);
  int p_in = 0;
  int att_in = 0;
  for (std::size_t k = 0; k < kTimes; ++k) {
    p_in += p_nees[k] >= lo && p_nees[k] <= hi ? 1 : 0;
    att_in += att_nees[k] >= lo && att_nees[k] <= hi ? 1 : 0;
  }
  EXPECT_GE(p_in, 18) << "position NEES at 20 s: " << p_nees[0];
  EXPECT_GE(att_in, 18) << "attitude NEES at 20 s: " << att_nees[0];
  const double p_mean = std::accumulate(p_nees.begin(), p_nees.end(), 0.0) / kTimes;
  const double att_mean = std::accumulate(att_nees.begin(), att_nees.end(), 0.0) / kTimes;
  EXPECT_NEAR(p_mean, 3.0, 0.6);
  EXPECT_NEAR(att_mean, 3.0, 0.6);
}

// GIVEN a settled filter WHEN fixes jump 3 m away for a second THEN every one is refused and
// counted, and the estimate stays within 10 cm of the truth.
TEST(ErrorStateFilter, AJumpInThePositionFixesIsRejectedAndCounted)
{
  test::Sensors sensors;
  ErrorStateFilter jumped(movingStart());
  double worst = 0.0;
  std::uint64_t rejected_before = 0;
  const auto motion = test::constantVelocity({0, 0, 2}, {1.5, 0, 0}, 0.0);
  // Offsetting the truth the position sensor sees, and only it: the fixes come from a
  // sensor that measures p + jump, so the test flies a motion whose position jumps while its
  // velocity and the IMU do not.
  const auto seen = [&](double t) {
    Truth x = motion(t);
    if (t >= 20.0 && t < 21.0) {
      x.p_W += Vector3(3.0, -1.0, 0.0);
    }
    return x;
  };
  test::fly(jumped, seen, 30.0, sensors, 4, [&](double t, const Truth&) {
    if (t > 10.0) {
      worst = std::max(worst, (jumped.estimate(0).p_W - motion(t).p_W).norm());
    }
    if (t < 20.0) {
      rejected_before = jumped.positionCounts().rejected;
    }
  });
  EXPECT_EQ(rejected_before, 0U);
  EXPECT_GE(jumped.positionCounts().rejected, 9U);
  EXPECT_LT(worst, 0.10);
}

// GIVEN a settled filter WHEN the fixes stop for 5 s THEN the position is no longer aided
// and its 1σ grows, while the IMU, the barometer and the magnetometer hold the error under
// a metre; when they come back it is aided again within one fix and the error falls back.
TEST(ErrorStateFilter, APositionDropoutIsFlownOnTheImuAndDeclared)
{
  ErrorStateFilter filter(movingStart());
  test::Sensors sensors;
  std::optional<bool> aided_in_gap;
  double std_in_gap = 0.0;
  double err_in_gap = 0.0;
  double err_after = 0.0;
  test::fly(
      filter, test::coordinatedTurn({0, 0, 3}, 10.0, 2.0), 40.0, sensors, 5,
      [&](double t, const Truth& x) {
        const auto now = static_cast<std::int64_t>(t * 1e9);
        const Estimate e = filter.estimate(now);
        if (t > 26.5 && t < 27.0) {
          aided_in_gap = e.health.position_aided;
          std_in_gap = e.p_std.head<2>().maxCoeff();
          err_in_gap = std::max(err_in_gap, (e.p_W - x.p_W).norm());
        }
        if (t > 35.0) {
          err_after = std::max(err_after, (e.p_W - x.p_W).norm());
        }
      },
      [&](double t, test::Sensors& s) { s.position.enabled = !(t >= 22.0 && t < 27.0); });
  ASSERT_TRUE(aided_in_gap);
  EXPECT_FALSE(*aided_in_gap);
  EXPECT_GT(std_in_gap, 0.1);
  EXPECT_LT(err_in_gap, 1.0);
  EXPECT_LT(err_after, 0.1);
  EXPECT_TRUE(filter.health(40'000'000'000).position_aided);
}

// Bad samples are refused, counted, and change nothing.
TEST(ErrorStateFilter, NonFiniteAndOutOfOrderSamplesAreRefusedAndCounted)
{
  ErrorStateFilter filter(movingStart());
  test::fly(filter, test::constantVelocity({0, 0, 2}, Vector3::Zero(), 0.0), 5.0, {}, 6);
  const Estimate before = filter.estimate(5'000'000'000);
  const double nan = std::nan("");
  EXPECT_EQ(filter.imu(5'004'000'000, Vector3(nan, 0, 9.8), Vector3::Zero()), Update::kBadInput);
  EXPECT_EQ(filter.imu(4'000'000'000, Vector3(0, 0, 9.8), Vector3::Zero()), Update::kBadInput);
  EXPECT_EQ(filter.position(4'990'000'000, Vector3(0, 0, nan), 0.02), Update::kBadInput);
  EXPECT_EQ(filter.position(4'990'000'000, Vector3(0, 0, 2), -1.0), Update::kBadInput);
  EXPECT_EQ(filter.position(1'000'000'000, Vector3(0, 0, 2), 0.02), Update::kTooOld);
  EXPECT_EQ(filter.baro(5'000'000'000, nan, 0.1), Update::kBadInput);
  EXPECT_EQ(filter.mag(5'000'000'000, Vector3(nan, 1, 1), 0.3), Update::kBadInput);
  const Estimate after = filter.estimate(5'000'000'000);
  EXPECT_EQ(after.p_W, before.p_W);
  EXPECT_EQ(filter.imuCounts().bad, 2U);
  EXPECT_EQ(filter.positionCounts().bad, 3U);  // the old fix too
  EXPECT_EQ(filter.baroCounts().bad, 1U);
  EXPECT_EQ(filter.magCounts().bad, 1U);
}

// The Eigen-only filter is the same filter: the same inputs give the same estimate.
TEST(ErrorStateFilter, TheEigenOnlyFilterAgreesWithMrpts)
{
  ErrorStateFilter mrpt(movingStart());
  BasicErrorStateFilter<EigenRotations> eigen(movingStart());
  test::fly(mrpt, test::coordinatedTurn({0, 0, 3}, 10.0, 3.0), 20.0, {}, 7);
  test::fly(eigen, test::coordinatedTurn({0, 0, 3}, 10.0, 3.0), 20.0, {}, 7);
  EXPECT_LT((mrpt.estimate(0).p_W - eigen.estimate(0).p_W).norm(), 1e-6);
  EXPECT_LT((mrpt.covariance() - eigen.covariance()).norm(), 1e-7 * mrpt.covariance().norm());
}

}  // namespace
}  // namespace quad::estimation
