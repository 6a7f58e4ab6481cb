// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// An error-state Kalman filter for a multirotor (Solà, "Quaternion kinematics for the
/// error-state Kalman filter", 2017, §5-§7; attitude error in the world frame, §7.2): the
/// IMU drives the prediction of position, velocity and attitude; absolute position fixes,
/// barometric altitude and the magnetometer's field vector correct it. The error state (16):
/// δp, δv [m, m/s, world], δθ [rad, world], accelerometer and gyroscope biases [body], and
/// the barometer's offset [m]. Every update is gated on its innovation's Mahalanobis
/// distance (a χ² quantile); rejected ones are counted. A position fix is stamped when it
/// was measured: its innovation is taken against the position the filter had then.
/// Time enters as arguments (sim time in ns); nothing here reads a clock.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "quad/estimation/estimator_params.hpp"
#include "quad/estimation/rotations.hpp"
#include "quad/geometry/quaternion.hpp"

namespace quad::estimation {

inline constexpr int kStateSize = 16;
using StateVector = Eigen::Matrix<double, kStateSize, 1>;
using Covariance = Eigen::Matrix<double, kStateSize, kStateSize>;

/// Where each error block starts in the state.
enum Block : int { kPosition = 0, kVelocity = 3, kAttitude = 6, kAccelBias = 9, kGyroBias = 12, kBaroOffset = 15 };

/// How an update went.
enum class Update { kAccepted, kRejected, kNotAligned, kBadInput, kTooOld };
std::string_view toString(Update u);

/// Per aid: taken, and refused by the gate.
struct AidCounts {
  std::uint64_t accepted = 0;
  std::uint64_t rejected = 0;
  std::uint64_t bad = 0;  ///< not finite, out of order, or stamped outside the history
};

struct Health {
  bool aligned = false;          ///< the filter has an initial state
  bool position_aided = false;   ///< a fix taken within params.position_timeout
  bool heading_aided = false;    ///< a heading taken within params.heading_timeout
  bool covariance_ok = false;    ///< position and attitude 1σ within their bounds
  bool imu_ok = false;           ///< an IMU sample within params.imu_timeout
  /// Fit to fly on: aligned, the IMU alive and the covariance within bounds.
  bool ok() const { return aligned && imu_ok && covariance_ok; }
};

struct Estimate {
  std::int64_t t_ns = 0;                        ///< the newest IMU sample's time
  Vector3 p_W = Vector3::Zero();                ///< [m]
  Vector3 v_W = Vector3::Zero();                ///< [m/s]
  geometry::Quaternion q_WB;                    ///< body to world
  Vector3 w_B = Vector3::Zero();                ///< [rad/s] the gyroscope less its bias
  Vector3 a_W = Vector3::Zero();                ///< [m/s²] the accelerometer less its bias, with gravity
  Vector3 accel_bias_B = Vector3::Zero();       ///< [m/s²]
  Vector3 gyro_bias_B = Vector3::Zero();        ///< [rad/s]
  double baro_offset = 0.0;                     ///< [m]
  Vector3 p_std = Vector3::Zero();              ///< [m] 1σ per axis
  Vector3 v_std = Vector3::Zero();              ///< [m/s]
  Vector3 attitude_std = Vector3::Zero();       ///< [rad] about world x, y, z
  Health health;
};

template <class Rotations>
class BasicErrorStateFilter {
public:
  /// Throws common::ConfigError via the params' own check (estimatorParamsFrom) only; the
  /// constructor takes them as given.
  explicit BasicErrorStateFilter(EstimatorParams params);

  const EstimatorParams& params() const { return params_; }
  bool aligned() const { return aligned_; }

  /// An IMU sample at `t_ns`: specific force [m/s²] and angular rate [rad/s], body frame.
  /// Before alignment it is kept for it; after, it predicts from the previous sample's time.
  Update imu(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B);
  /// A position fix measured at `t_ns` (it may arrive later), 1σ `std_dev` [m] per axis.
  /// Refused by the gate while the position is still aided; once it has gone unaided past
  /// params.position_timeout, a refused fix resets the position to it (the velocity's
  /// variance back to its initial one) and counts as taken.
  Update position(std::int64_t t_ns, const Vector3& p_W, double std_dev);
  /// Barometric altitude [m] at `t_ns`, 1σ `std_dev` [m].
  Update baro(std::int64_t t_ns, double altitude, double std_dev);
  /// The magnetometer's field [µT, body] at `t_ns`, 1σ `std_dev` [µT] per axis.
  Update mag(std::int64_t t_ns, const Vector3& field_B, double std_dev);

  /// The estimate as of the newest IMU sample; health judged at `now_ns`.
  Estimate estimate(std::int64_t now_ns) const;
  /// [ns] The newest IMU sample's time: the estimate's; -1 before the first.
  std::int64_t timeNs() const { return t_ns_; }
  Health health(std::int64_t now_ns) const;
  const Covariance& covariance() const { return P_; }
  const AidCounts& positionCounts() const { return position_counts_; }
  const AidCounts& baroCounts() const { return baro_counts_; }
  const AidCounts& magCounts() const { return mag_counts_; }
  const AidCounts& imuCounts() const { return imu_counts_; }
  /// Times the position started over from a fix, unaided past the timeout (position()).
  std::uint64_t positionResets() const { return position_resets_; }

private:
  /// Aligns when the samples kept allow it (at rest, falling, or waited moving_after).
  void align(std::int64_t t_ns);
  /// Before alignment: whether the IMU sample reads as at rest, kept for it.
  void keepForAlignment(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B);
  void predict(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B);
  /// The gated update with innovation `y`, Jacobian `H` and noise `R`; applies it when the
  /// innovation passes `gate`.
  template <int M>
  bool correct(const Eigen::Matrix<double, M, 1>& y, const Eigen::Matrix<double, M, kStateSize>& H,
               const Eigen::Matrix<double, M, M>& R, double gate);
  void inject(const StateVector& dx);

  EstimatorParams params_;
  double gate_1_;  // χ² quantiles of the gate probability, 1 and 3 degrees of freedom
  double gate_3_;
  bool aligned_ = false;
  // Before alignment: the newest fixes (the rest window's, two at least) and the first one's
  // time; the run of IMU samples that read as at rest (since when, and the forces of its
  // last second and rest window); the newest force and field.
  std::deque<std::pair<std::int64_t, Vector3>> fixes_;
  std::int64_t first_fix_ns_ = -1;
  std::int64_t rest_since_ns_ = -1;
  std::deque<std::pair<std::int64_t, Vector3>> rest_forces_;
  std::optional<Vector3> newest_force_;
  std::optional<Vector3> newest_field_;
  std::optional<double> first_baro_;

  Vector3 p_ = Vector3::Zero();
  Vector3 v_ = Vector3::Zero();
  Matrix3 R_ = Matrix3::Identity();
  Vector3 ba_ = Vector3::Zero();
  Vector3 bg_ = Vector3::Zero();
  double bb_ = 0.0;
  bool baro_offset_set_ = false;
  Covariance P_ = Covariance::Zero();
  std::int64_t t_ns_ = -1;               // newest IMU sample
  Vector3 w_last_ = Vector3::Zero();      // its rate and force, less the biases
  Vector3 a_last_W_ = Vector3::Zero();
  std::deque<std::pair<std::int64_t, Vector3>> history_;  // position after each prediction
  std::int64_t last_fix_ns_ = -1;
  std::int64_t last_heading_ns_ = -1;
  AidCounts position_counts_;
  AidCounts baro_counts_;
  AidCounts mag_counts_;
  AidCounts imu_counts_;
  std::uint64_t position_resets_ = 0;
};

/// The stack's filter: SO(3) from MRPT.
using ErrorStateFilter = BasicErrorStateFilter<MrptRotations>;

}  // namespace quad::estimation
