// SPDX-License-Identifier: BSD-3-Clause
#include "quad/estimation/error_state_filter.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <mrpt/math/distributions.h>

#include "quad/common/time.hpp"
#include "quad/geometry/so3.hpp"

namespace quad::estimation {

namespace {

using geometry::hat;

bool finite(const Vector3& v) { return v.allFinite(); }

/// Heading of a vector's horizontal part [rad], from world x towards y.
double headingOf(const Vector3& v) { return std::atan2(v.y(), v.x()); }

using Samples = std::deque<std::pair<std::int64_t, Vector3>>;

/// The least-squares slope [per s] of the samples stamped at or after `from_ns` (zero for
/// fewer than two).
Vector3 slopeSince(const Samples& samples, std::int64_t from_ns)
{
  Vector3 mean = Vector3::Zero();
  double t_mean = 0.0;
  int n = 0;
  for (const auto& [t, x] : samples) {
    if (t >= from_ns) {
      mean += x;
      t_mean += common::toSeconds(t - from_ns);
      ++n;
    }
  }
  if (n < 2) {
    return Vector3::Zero();
  }
  mean /= n;
  t_mean /= n;
  Vector3 tx = Vector3::Zero();
  double tt = 0.0;
  for (const auto& [t, x] : samples) {
    if (t >= from_ns) {
      const double dt = common::toSeconds(t - from_ns) - t_mean;
      tx += dt * (x - mean);
      tt += dt * dt;
    }
  }
  return tt > 0.0 ? Vector3(tx / tt) : Vector3::Zero();
}

/// The mean of the samples stamped at or after `from_ns`; none without one.
std::optional<Vector3> meanSince(const Samples& samples, std::int64_t from_ns)
{
  Vector3 sum = Vector3::Zero();
  int n = 0;
  for (const auto& [t, x] : samples) {
    if (t >= from_ns) {
      sum += x;
      ++n;
    }
  }
  return n > 0 ? std::optional<Vector3>(sum / n) : std::nullopt;
}

}  // namespace

std::string_view toString(Update u)
{
  switch (u) {
    case Update::kAccepted:
      return "accepted";
    case Update::kRejected:
      return "rejected by the gate";
    case Update::kNotAligned:
      return "kept for alignment";
    case Update::kBadInput:
      return "bad input";
    case Update::kTooOld:
      return "too old";
  }
  return "?";
}

template <class Rotations>
BasicErrorStateFilter<Rotations>::BasicErrorStateFilter(EstimatorParams params)
    : params_(params),
      gate_1_(mrpt::math::chi2inv(params.gate_probability, 1)),
      gate_3_(mrpt::math::chi2inv(params.gate_probability, 3))
{
}

template <class Rotations>
Update BasicErrorStateFilter<Rotations>::imu(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B)
{
  if (!finite(f_B) || !finite(w_B) || t_ns <= t_ns_) {
    ++imu_counts_.bad;
    return Update::kBadInput;
  }
  ++imu_counts_.accepted;
  if (!aligned_) {
    keepForAlignment(t_ns, f_B, w_B);
    t_ns_ = t_ns;
    align(t_ns);
    return aligned_ ? Update::kAccepted : Update::kNotAligned;
  }
  predict(t_ns, f_B, w_B);
  return Update::kAccepted;
}

template <class Rotations>
void BasicErrorStateFilter<Rotations>::keepForAlignment(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B)
{
  newest_force_ = f_B;
  const bool still = std::abs(f_B.norm() - params_.gravity_W.norm()) <= params_.rest_tolerance &&
                     w_B.norm() <= params_.rest_rate;
  if (!still) {
    rest_since_ns_ = -1;
    rest_forces_.clear();
    return;
  }
  if (rest_since_ns_ < 0) {
    rest_since_ns_ = t_ns;
  }
  rest_forces_.emplace_back(t_ns, f_B);
  // The fixes come late (their latency): a second more than the window is kept for them.
  while (rest_forces_.front().first < t_ns - common::toNanoseconds(params_.rest_window + 1.0)) {
    rest_forces_.pop_front();
  }
}

template <class Rotations>
void BasicErrorStateFilter<Rotations>::align(std::int64_t t_ns)
{
  if (fixes_.size() < 2 || !newest_force_ || !newest_field_) {
    return;
  }
  // The fixes of the rest window (two at least), fitted with a line: their velocity.
  const std::int64_t newest_ns = fixes_.back().first;
  const std::int64_t window_ns =
      std::min(newest_ns - common::toNanoseconds(params_.rest_window), fixes_[fixes_.size() - 2].first);
  const Vector3 fix_velocity = slopeSince(fixes_, window_ns);

  // At rest the accelerometer reads −g in the body: roll and pitch. The magnetometer, levelled
  // with them, gives the yaw against the local field's heading. In flight it reads the thrust,
  // along the body's z whatever the tilt: alignment waits for rest (the controller holds the
  // vehicle while it has no state), all of the window long.
  // Falling (a start in the air), the tilt cannot be told and nothing is worth waiting for:
  // level, with a wide 1σ, and the velocity's wide too; the fixes and the accelerometer then
  // pull both in. The same after moving_after without rest.
  const bool at_rest = rest_since_ns_ >= 0 && rest_since_ns_ <= window_ns &&
                       fix_velocity.norm() <= params_.rest_speed;
  const bool falling = newest_force_->norm() < params_.gravity_W.norm() - params_.rest_tolerance;
  const bool waited = newest_ns - first_fix_ns_ >= common::toNanoseconds(params_.moving_after);
  if (!at_rest && !falling && !waited) {
    return;
  }
  // At rest, the tilt from the window's mean force (the noise averaged out).
  const Vector3 f = at_rest ? meanSince(rest_forces_, window_ns).value_or(*newest_force_) : *newest_force_;
  const double roll = at_rest ? std::atan2(f.y(), f.z()) : 0.0;
  const double pitch = at_rest ? std::atan2(-f.x(), std::hypot(f.y(), f.z())) : 0.0;
  const Matrix3 tilt = geometry::rotY(pitch) * geometry::rotX(roll);
  const double yaw = geometry::wrapToPi(headingOf(params_.mag_field_W) - headingOf(tilt * *newest_field_));
  R_ = geometry::rotZ(yaw) * tilt;
  p_ = fixes_.back().second + fix_velocity * common::toSeconds(t_ns - newest_ns);  // a fix is late
  v_ = fix_velocity;
  ba_.setZero();
  bg_.setZero();
  P_.setZero();
  const auto block = [&](int at, double std_dev) { P_.block<3, 3>(at, at) = Matrix3::Identity() * std_dev * std_dev; };
  block(kPosition, 0.05);
  block(kVelocity, at_rest ? params_.initial_velocity_std : params_.moving_velocity_std);
  block(kAttitude, at_rest ? params_.initial_tilt_std : params_.moving_tilt_std);
  // The heading is the field's levelled with the tilt: a tilt off by δ turns it by about
  // δ times the field's vertical over its horizontal part (2 here, the field dipping 64°).
  const Vector3& m = params_.mag_field_W;
  const double yaw_std =
      at_rest ? params_.initial_yaw_std
              : std::min(std::numbers::pi, std::hypot(params_.initial_yaw_std,
                                                      params_.moving_tilt_std * std::abs(m.z()) /
                                                          std::max(m.head<2>().norm(), 1e-9)));
  P_(kAttitude + 2, kAttitude + 2) = yaw_std * yaw_std;
  block(kAccelBias, params_.accel_bias_prior);
  block(kGyroBias, params_.gyro_bias_prior);
  if (first_baro_) {
    bb_ = *first_baro_ - p_.z();
    baro_offset_set_ = true;
  }
  P_(kBaroOffset, kBaroOffset) = params_.baro_offset_prior * params_.baro_offset_prior;
  t_ns_ = t_ns;
  last_fix_ns_ = newest_ns;
  last_heading_ns_ = t_ns;
  history_.assign(1, {t_ns, p_});
  aligned_ = true;
}

template <class Rotations>
void BasicErrorStateFilter<Rotations>::predict(std::int64_t t_ns, const Vector3& f_B, const Vector3& w_B)
{
  // A gap (a lost sample, a pause) is integrated as one step, but never longer than 0.1 s:
  // beyond that the sample says little of the interval.
  const double dt = std::min(common::toSeconds(t_ns - t_ns_), 0.1);
  const Vector3 f = f_B - ba_;
  const Vector3 w = w_B - bg_;
  const Vector3 f_W = R_ * f;
  const Vector3 a_W = f_W + params_.gravity_W;

  // The error's transition, first order in dt (attitude error in the world frame: a gyro bias
  // error turns the attitude by R δb_g dt, and the attitude error tilts the measured force).
  Covariance F = Covariance::Identity();
  F.block<3, 3>(kPosition, kVelocity) = Matrix3::Identity() * dt;
  F.block<3, 3>(kVelocity, kAttitude) = -hat(f_W) * dt;
  F.block<3, 3>(kVelocity, kAccelBias) = -R_ * dt;
  F.block<3, 3>(kAttitude, kGyroBias) = -R_ * dt;
  P_ = F * P_ * F.transpose();
  // White noise per sample integrates into velocity and attitude; the walks per √s.
  const double qv = std::pow(params_.accel_noise * dt, 2);
  const double qt = std::pow(params_.gyro_noise * dt, 2);
  for (int i = 0; i < 3; ++i) {
    P_(kVelocity + i, kVelocity + i) += qv;
    P_(kAttitude + i, kAttitude + i) += qt;
    P_(kAccelBias + i, kAccelBias + i) += params_.accel_bias_walk * params_.accel_bias_walk * dt;
    P_(kGyroBias + i, kGyroBias + i) += params_.gyro_bias_walk * params_.gyro_bias_walk * dt;
  }
  P_(kBaroOffset, kBaroOffset) += params_.baro_drift * params_.baro_drift * dt;

  p_ += v_ * dt + 0.5 * a_W * dt * dt;
  v_ += a_W * dt;
  R_ = R_ * Rotations::exp(w * dt);
  t_ns_ = t_ns;
  w_last_ = w;
  a_last_W_ = a_W;
  history_.emplace_back(t_ns, p_);
  const std::int64_t keep_ns = common::toNanoseconds(params_.max_fix_age) + 1;
  while (history_.size() > 1 && history_.front().first < t_ns - keep_ns) {
    history_.pop_front();
  }
}

template <class Rotations>
template <int M>
bool BasicErrorStateFilter<Rotations>::correct(const Eigen::Matrix<double, M, 1>& y,
                                               const Eigen::Matrix<double, M, kStateSize>& H,
                                               const Eigen::Matrix<double, M, M>& R, double gate)
{
  const Eigen::Matrix<double, M, M> S = H * P_ * H.transpose() + R;
  const Eigen::LDLT<Eigen::Matrix<double, M, M>> S_ldlt(S);
  if (S_ldlt.info() != Eigen::Success) {
    return false;
  }
  const double nis = y.dot(S_ldlt.solve(y));
  if (!(nis <= gate)) {
    return false;
  }
  const Eigen::Matrix<double, kStateSize, M> K = S_ldlt.solve(H * P_).transpose();  // P Hᵀ S⁻¹ (S, P symmetric)
  inject(K * y);
  // Joseph's form keeps P symmetric and positive through rounding.
  const Covariance I_KH = Covariance::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
  return true;
}

template <class Rotations>
void BasicErrorStateFilter<Rotations>::inject(const StateVector& dx)
{
  const Vector3 dp = dx.segment<3>(kPosition);
  p_ += dp;
  v_ += dx.segment<3>(kVelocity);
  R_ = Rotations::exp(dx.segment<3>(kAttitude)) * R_;
  ba_ += dx.segment<3>(kAccelBias);
  bg_ += dx.segment<3>(kGyroBias);
  bb_ += dx(kBaroOffset);
  // The positions remembered for late fixes move with the correction: a fix is compared with
  // the path as it is now known.
  for (auto& h : history_) {
    h.second += dp;
  }
}

template <class Rotations>
Update BasicErrorStateFilter<Rotations>::position(std::int64_t t_ns, const Vector3& p_W, double std_dev)
{
  if (!finite(p_W) || !(std_dev > 0.0) || !std::isfinite(std_dev)) {
    ++position_counts_.bad;
    return Update::kBadInput;
  }
  if (!aligned_) {
    if (!fixes_.empty() && t_ns <= fixes_.back().first) {
      ++position_counts_.bad;
      return Update::kBadInput;
    }
    fixes_.emplace_back(t_ns, p_W);
    first_fix_ns_ = first_fix_ns_ < 0 ? t_ns : first_fix_ns_;
    while (fixes_.size() > 2 && fixes_[1].first < t_ns - common::toNanoseconds(params_.rest_window)) {
      fixes_.pop_front();
    }
    align(t_ns_);
    return aligned_ ? Update::kAccepted : Update::kNotAligned;
  }
  // The position the filter had when the fix was measured: the newest remembered at or
  // before its stamp (the IMU's period apart at most).
  if (t_ns > t_ns_ + common::toNanoseconds(0.01) || t_ns < history_.front().first) {
    ++position_counts_.bad;
    return t_ns > t_ns_ ? Update::kBadInput : Update::kTooOld;
  }
  auto at = std::upper_bound(history_.begin(), history_.end(), t_ns,
                             [](std::int64_t t, const auto& h) { return t < h.first; });
  const Vector3& p_then = (at == history_.begin() ? at : std::prev(at))->second;
  const Vector3 y = p_W - p_then;
  // The error then, in terms of the error now: δp(t) ≈ δp − δv (now − t).
  Eigen::Matrix<double, 3, kStateSize> H = Eigen::Matrix<double, 3, kStateSize>::Zero();
  H.block<3, 3>(0, kPosition).setIdentity();
  H.block<3, 3>(0, kVelocity) = -Matrix3::Identity() * common::toSeconds(std::max<std::int64_t>(0, t_ns_ - t_ns));
  const Matrix3 R = Matrix3::Identity() * std_dev * std_dev;
  if (!correct<3>(y, H, R, gate_3_)) {
    ++position_counts_.rejected;
    if (t_ns - last_fix_ns_ <= common::toNanoseconds(params_.position_timeout)) {
      return Update::kRejected;
    }
    // Unaided past the timeout and still refusing fixes: the estimate has drifted off, and
    // the gate would shut out the truth for ever. Start the position over from this fix (as
    // PX4's EKF2 resets after a fusion timeout), and forget what was known of the velocity.
    p_ += y;
    for (auto& h : history_) {
      h.second += y;
    }
    for (const int block : {kPosition, kVelocity}) {
      P_.middleRows<3>(block).setZero();
      P_.middleCols<3>(block).setZero();
    }
    P_.block<3, 3>(kPosition, kPosition) = R;
    P_.block<3, 3>(kVelocity, kVelocity) = Matrix3::Identity() * params_.initial_velocity_std * params_.initial_velocity_std;
    ++position_resets_;
  } else {
    ++position_counts_.accepted;
  }
  last_fix_ns_ = std::max(last_fix_ns_, t_ns);
  return Update::kAccepted;
}

template <class Rotations>
Update BasicErrorStateFilter<Rotations>::baro(std::int64_t t_ns, double altitude, double std_dev)
{
  if (!std::isfinite(altitude) || !(std_dev > 0.0) || !std::isfinite(std_dev)) {
    ++baro_counts_.bad;
    return Update::kBadInput;
  }
  if (!aligned_) {
    first_baro_ = altitude;
    return Update::kNotAligned;
  }
  if (!baro_offset_set_) {
    bb_ = altitude - p_.z();
    baro_offset_set_ = true;
    ++baro_counts_.accepted;
    return Update::kAccepted;
  }
  (void)t_ns;  // taken as of the newest IMU sample (a barometer has no latency worth modelling)
  Eigen::Matrix<double, 1, 1> y;
  y(0) = altitude - (p_.z() + bb_);
  Eigen::Matrix<double, 1, kStateSize> H = Eigen::Matrix<double, 1, kStateSize>::Zero();
  H(0, kPosition + 2) = 1.0;
  H(0, kBaroOffset) = 1.0;
  Eigen::Matrix<double, 1, 1> R;
  R(0) = std_dev * std_dev;
  if (!correct<1>(y, H, R, gate_1_)) {
    ++baro_counts_.rejected;
    return Update::kRejected;
  }
  ++baro_counts_.accepted;
  return Update::kAccepted;
}

template <class Rotations>
Update BasicErrorStateFilter<Rotations>::mag(std::int64_t t_ns, const Vector3& field_B, double std_dev)
{
  if (!finite(field_B) || !(std_dev > 0.0) || !std::isfinite(std_dev)) {
    ++mag_counts_.bad;
    return Update::kBadInput;
  }
  if (!aligned_) {
    newest_field_ = field_B;
    align(t_ns_);
    return aligned_ ? Update::kAccepted : Update::kNotAligned;
  }
  // The whole vector: the field read is the local field turned into the body,
  // m_B = R_WBᵀ m_W; turning the estimate by δθ (world) changes it by R̂ᵀ[m_W]× δθ. It
  // fixes the yaw, and (the field dips 64° here) the tilt with it. Fusing only a yaw (the
  // field levelled with the estimate's roll and pitch, as PX4's EKF2 can) was tried first:
  // the tilt's error leaks into such a yaw twice over (|m_z|/h), and the filter, kept blind
  // to that, was confident in yaws 2° off in a turn.
  const Vector3 y = field_B - R_.transpose() * params_.mag_field_W;
  Eigen::Matrix<double, 3, kStateSize> H = Eigen::Matrix<double, 3, kStateSize>::Zero();
  H.block<3, 3>(0, kAttitude) = R_.transpose() * hat(params_.mag_field_W);
  const Matrix3 R = Matrix3::Identity() * std_dev * std_dev;
  if (!correct<3>(y, H, R, gate_3_)) {
    ++mag_counts_.rejected;
    return Update::kRejected;
  }
  ++mag_counts_.accepted;
  last_heading_ns_ = std::max(last_heading_ns_, t_ns);
  return Update::kAccepted;
}

template <class Rotations>
Health BasicErrorStateFilter<Rotations>::health(std::int64_t now_ns) const
{
  Health h;
  h.aligned = aligned_;
  if (!aligned_) {
    return h;
  }
  const auto within = [&](std::int64_t t, double timeout_s) { return t >= 0 && now_ns - t <= common::toNanoseconds(timeout_s); };
  h.imu_ok = within(t_ns_, params_.imu_timeout);
  h.position_aided = within(last_fix_ns_, params_.position_timeout);
  h.heading_aided = within(last_heading_ns_, params_.heading_timeout);
  const double p_std = std::sqrt(P_.diagonal().segment<3>(kPosition).maxCoeff());
  const double att_std = std::sqrt(P_.diagonal().segment<3>(kAttitude).maxCoeff());
  h.covariance_ok = p_std <= params_.max_position_std && att_std <= params_.max_attitude_std;
  return h;
}

template <class Rotations>
Estimate BasicErrorStateFilter<Rotations>::estimate(std::int64_t now_ns) const
{
  Estimate e;
  e.t_ns = t_ns_;
  e.p_W = p_;
  e.v_W = v_;
  e.q_WB = geometry::fromMatrix(R_);
  e.w_B = w_last_;
  e.a_W = a_last_W_;
  e.accel_bias_B = ba_;
  e.gyro_bias_B = bg_;
  e.baro_offset = bb_;
  const StateVector var = P_.diagonal();
  e.p_std = var.segment<3>(kPosition).cwiseSqrt();
  e.v_std = var.segment<3>(kVelocity).cwiseSqrt();
  e.attitude_std = var.segment<3>(kAttitude).cwiseSqrt();
  e.health = health(now_ns);
  return e;
}

template class BasicErrorStateFilter<MrptRotations>;
template class BasicErrorStateFilter<EigenRotations>;

}  // namespace quad::estimation
