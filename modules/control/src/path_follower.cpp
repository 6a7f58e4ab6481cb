// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/path_follower.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "quad/geometry/so3.hpp"

namespace quad::control {

namespace {

constexpr double kCreepSpeed = 0.02;  // [m/s] the slowest the reference moves before the end

struct Sample {
  Vector3 p;
  Vector3 tangent;
  Vector3 normal;
  double curvature;
};

/// Appends the straight segment a → b (excluding a) at the given spacing.
void line(const Vector3& a, const Vector3& b, double spacing, std::vector<Sample>& out)
{
  const double len = (b - a).norm();
  if (len < 1e-9) {
    return;
  }
  const Vector3 t = (b - a) / len;
  const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
  for (int i = 1; i <= n; ++i) {
    out.push_back({a + (b - a) * (static_cast<double>(i) / n), t, Vector3::Zero(), 0.0});
  }
}

/// Appends the quadratic Bézier P0 → P2 with control point P1 (excluding P0).
void blend(const Vector3& P0, const Vector3& P1, const Vector3& P2, double spacing, std::vector<Sample>& out)
{
  const double approx = (P1 - P0).norm() + (P2 - P1).norm();
  const int n = std::max(2, static_cast<int>(std::ceil(approx / spacing)));
  for (int i = 1; i <= n; ++i) {
    const double u = static_cast<double>(i) / n;
    const Vector3 p = (1 - u) * (1 - u) * P0 + 2 * (1 - u) * u * P1 + u * u * P2;
    const Vector3 d1 = 2 * (1 - u) * (P1 - P0) + 2 * u * (P2 - P1);
    const Vector3 d2 = 2 * (P2 - 2 * P1 + P0);
    const double speed = d1.norm();
    Sample s{p, speed > 1e-12 ? Vector3(d1 / speed) : Vector3((P2 - P0).normalized()), Vector3::Zero(), 0.0};
    if (speed > 1e-12) {
      const Vector3 cross = d1.cross(d2);
      s.curvature = cross.norm() / (speed * speed * speed);
      const Vector3 n_dir = d2 - d2.dot(s.tangent) * s.tangent;
      if (n_dir.norm() > 1e-12) {
        s.normal = n_dir.normalized();
      }
    } else {
      s.curvature = 1e6;  // a cusp: the profile stops there
    }
    out.push_back(s);
  }
}

}  // namespace

Trajectory::Trajectory(std::vector<Vector3> waypoints, const FollowerLimits& limits, double start_speed)
{
  for (const Vector3& w : waypoints) {
    if (waypoints_.empty() || (w - waypoints_.back()).norm() > 1e-6) {
      waypoints_.push_back(w);
    }
  }
  if (waypoints_.empty()) {
    waypoints_.push_back(Vector3::Zero());
  }
  std::vector<Sample> samples{{waypoints_.front(), Vector3::UnitX(), Vector3::Zero(), 0.0}};
  if (waypoints_.size() >= 2) {
    samples.front().tangent = (waypoints_[1] - waypoints_[0]).normalized();
    // Blend distance at each interior corner: the curve's deviation from the polyline is
    // ¼ d sin φ (φ the interior angle), and neighbouring blends must not overlap.
    const std::size_t n = waypoints_.size();
    std::vector<double> d(n, 0.0);
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const Vector3 in = waypoints_[i] - waypoints_[i - 1];
      const Vector3 out = waypoints_[i + 1] - waypoints_[i];
      const double cos_turn = std::clamp(in.normalized().dot(out.normalized()), -1.0, 1.0);
      const double sin_interior = std::sqrt(std::max(0.0, 1.0 - cos_turn * cos_turn));
      const double by_deviation = sin_interior > 1e-9 ? 4.0 * limits.corner_deviation / sin_interior : 1e9;
      d[i] = std::min({by_deviation, 0.5 * in.norm(), 0.5 * out.norm()});
    }
    Vector3 cursor = waypoints_[0];
    for (std::size_t i = 1; i < n; ++i) {
      const Vector3 dir = (waypoints_[i] - waypoints_[i - 1]).normalized();
      const Vector3 blend_start = waypoints_[i] - d[i] * dir;
      line(cursor, blend_start, limits.sample_spacing, samples);
      cursor = blend_start;
      if (i + 1 < n && d[i] > 0.0) {
        const Vector3 next_dir = (waypoints_[i + 1] - waypoints_[i]).normalized();
        const Vector3 blend_end = waypoints_[i] + d[i] * next_dir;
        blend(cursor, waypoints_[i], blend_end, limits.sample_spacing, samples);
        cursor = blend_end;
      }
    }
  }
  // Arc length, and the speed profile: curvature limit, then acceleration-limited forward
  // and backward passes (at 80 % of the limit, leaving room for the jerk-limited time law).
  s_.assign(samples.size(), 0.0);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    s_[i] = s_[i - 1] + (samples[i].p - samples[i - 1].p).norm();
  }
  length_ = s_.back();
  std::vector<double> v(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    v[i] = limits.max_speed;
    if (samples[i].curvature > 1e-9) {
      v[i] = std::min(v[i], std::sqrt(limits.max_lateral_acceleration / samples[i].curvature));
    }
  }
  const double a = 0.8 * limits.max_acceleration;
  v.front() = std::min(v.front(), std::max(0.0, start_speed));
  for (std::size_t i = 1; i < v.size(); ++i) {
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * a * (s_[i] - s_[i - 1])));
  }
  v.back() = 0.0;
  for (std::size_t i = v.size() - 1; i-- > 0;) {
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * a * (s_[i + 1] - s_[i])));
  }
  table_.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    table_.push_back({samples[i].p, samples[i].tangent, samples[i].normal, samples[i].curvature, v[i]});
  }
}

Trajectory::Point Trajectory::at(double s) const
{
  if (table_.size() == 1 || s <= 0.0) {
    return table_.front();
  }
  if (s >= length_) {
    return table_.back();
  }
  const auto it = std::upper_bound(s_.begin(), s_.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - s_.begin());
  const double span = s_[i] - s_[i - 1];
  const double u = span > 0.0 ? (s - s_[i - 1]) / span : 0.0;
  const Point& a = table_[i - 1];
  const Point& b = table_[i];
  Point p;
  p.p = a.p + u * (b.p - a.p);
  const Vector3 t = a.tangent + u * (b.tangent - a.tangent);
  p.tangent = t.norm() > 1e-12 ? Vector3(t.normalized()) : b.tangent;
  p.normal = u < 0.5 ? a.normal : b.normal;
  p.curvature = a.curvature + u * (b.curvature - a.curvature);
  p.speed_limit = a.speed_limit + u * (b.speed_limit - a.speed_limit);
  return p;
}

std::pair<std::size_t, std::size_t> Trajectory::samplesWithin(double from, double to) const
{
  const auto first = std::upper_bound(s_.begin(), s_.end(), from);
  const auto last = std::upper_bound(first, s_.end(), to);
  return {static_cast<std::size_t>(first - s_.begin()), static_cast<std::size_t>(last - s_.begin())};
}

double Trajectory::lowestSpeedLimit(double from, double to) const
{
  double lowest = at(from).speed_limit;
  const auto [first, last] = samplesWithin(from, to);
  for (std::size_t i = first; i < last; ++i) {
    lowest = std::min(lowest, table_[i].speed_limit);
  }
  return lowest;
}

double Trajectory::brakingNeeded(double s, double v, double horizon) const
{
  double needed = 0.0;
  const auto [first, last] = samplesWithin(s, s + horizon);
  for (std::size_t i = first; i < last; ++i) {
    // Overspeed of the order the time law itself runs into corners with is left to it.
    const double allowed = table_[i].speed_limit + 0.2;
    if (allowed < v) {
      needed = std::max(needed, (v * v - allowed * allowed) / (2.0 * std::max(s_[i] - s, 1e-3)));
    }
  }
  return needed;
}

PathFollower::PathFollower(FollowerLimits limits) : limits_(limits)
{
  limits_.max_braking = std::max(limits_.max_braking, limits_.max_acceleration);
}

bool PathFollower::setPath(const std::vector<Vector3>& waypoints, std::uint32_t version)
{
  if (waypoints.empty() ||
      std::any_of(waypoints.begin(), waypoints.end(), [](const Vector3& w) { return !w.allFinite(); })) {
    return false;
  }
  // Join the new polyline where it passes closest to the reference.
  std::size_t next = waypoints.size() > 1 ? 1 : 0;
  double best = (waypoints.front() - ref_.p_W).norm();
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Vector3 seg = waypoints[i + 1] - waypoints[i];
    const double len2 = seg.squaredNorm();
    const double u = len2 > 0.0 ? std::clamp((ref_.p_W - waypoints[i]).dot(seg) / len2, 0.0, 1.0) : 0.0;
    const double dist = (waypoints[i] + u * seg - ref_.p_W).norm();
    if (dist < best) {
      best = dist;
      next = i + 1;
    }
  }
  std::vector<Vector3> joined{ref_.p_W};
  const double speed = ref_.v_W.norm();
  if (speed > 0.05) {
    // Lead-in along the current motion, so the direction of the reference turns smoothly.
    const Vector3 heading = ref_.v_W / speed;
    Vector3 lead = ref_.p_W + heading * std::min(0.5, 0.5 * speed);
    // Replans can come faster than a lead-in is flown: a fresh one each time, always ahead,
    // would carry the reference on in its old direction for as long as they come (seen: a
    // second and a half of creep into a sphere every new path led away from). The last
    // lead-in, while still ahead and no farther than a fresh one, is kept.
    if (lead_in_ && (*lead_in_ - ref_.p_W).dot(ref_.v_W) > 0.0 &&
        (*lead_in_ - ref_.p_W).norm() <= (lead - ref_.p_W).norm() + 1e-9) {
      lead = *lead_in_;
    }
    // A path that turns back after the lead-in needs room to brake first: the lead-in is
    // then at least 1.2 v² / max_braking long (its turn's blend begins halfway along it).
    // Seen: a replan turning back 2 cm ahead of a reference at 0.9 m/s swung its velocity
    // round in 0.1 s, and the vehicle, lagging, into a tree.
    const double nearest = 1.2 * speed * speed / limits_.max_braking;
    const bool turns_back = (waypoints[next] - lead).dot(heading) < 0.0;
    if (turns_back && (lead - ref_.p_W).norm() < nearest) {
      lead = ref_.p_W + heading * nearest;
    }
    turn_back_end_ = turns_back ? (lead - ref_.p_W).norm() + 1.0 : 0.0;
    joined.push_back(lead);
    lead_in_ = lead;
  } else {
    lead_in_.reset();
    turn_back_end_ = 0.0;
  }
  joined.insert(joined.end(), waypoints.begin() + static_cast<std::ptrdiff_t>(next), waypoints.end());
  trajectory_.emplace(joined, limits_, speed);
  version_ = version;
  s_ = 0.0;
  v_ = speed;
  return true;
}

void PathFollower::hold(const Vector3& p, double yaw)
{
  trajectory_.emplace(std::vector<Vector3>{p}, limits_, 0.0);
  version_.reset();
  lead_in_.reset();
  turn_back_end_ = 0.0;
  s_ = 0.0;
  v_ = 0.0;
  a_ = 0.0;
  ref_ = Reference{p, Vector3::Zero(), Vector3::Zero(), yaw, 0.0};
}

bool PathFollower::finished() const
{
  return !trajectory_ || (s_ >= trajectory_->length() - 1e-6 && v_ < 1e-3);
}

Reference PathFollower::step(double dt)
{
  if (!trajectory_ || !(dt > 0.0)) {
    return ref_;
  }
  const Trajectory& traj = *trajectory_;
  // Jerk-limited tracking of the speed profile, looking ahead by the time the acceleration
  // needs to turn around.
  // (At least a few table samples ahead, so that it starts from rest; never past the end.)
  const double remaining = traj.length() - s_;
  const double lookahead = std::min(std::max(v_ * limits_.max_acceleration / limits_.max_jerk,
                                             2.0 * limits_.sample_spacing),
                                    0.5 * remaining);
  double v_target = traj.at(s_ + lookahead).speed_limit;
  const bool turning_back = s_ < turn_back_end_;
  if (turning_back) {
    // Through a turn back, the slowest point within the lookahead, not only its end (which
    // can lie past the turn).
    v_target = std::min(v_target, traj.lowestSpeedLimit(s_, s_ + lookahead));
  }
  // Brake for the end in time: the stopping distance with the jerk limit (ramping from the
  // current acceleration to full braking takes (a + a_max)/j).
  const double a_brake = 0.8 * limits_.max_acceleration;
  const double ramp = (std::max(a_, 0.0) + a_brake) / limits_.max_jerk;
  const double stopping = 1.3 * (v_ * ramp + v_ * v_ / (2.0 * a_brake));  // with a margin
  if (remaining <= stopping) {
    v_target = 0.0;
  }
  if (remaining > 0.0) {
    // The profile reaches zero only at the end: creep the last millimetres instead of
    // approaching the end asymptotically.
    v_target = std::max(v_target, std::min(kCreepSpeed, std::sqrt(limits_.max_acceleration * remaining)));
  }
  const double a_wanted = std::clamp(3.0 * (v_target - v_), -limits_.max_acceleration, limits_.max_acceleration);
  const double jerk = std::clamp((a_wanted - a_) / dt, -limits_.max_jerk, limits_.max_jerk);
  a_ += jerk * dt;
  // A path joined while moving that turns back after its lead-in: brake at once, as hard as
  // it takes (up to max_braking), so that the turn is not flown faster than its speed
  // profile allows. Until a metre past the turn.
  if (turning_back) {
    const double braking = traj.brakingNeeded(s_, v_, v_ * v_ / (2.0 * a_brake) + 2.0 * limits_.sample_spacing);
    if (braking > limits_.max_acceleration) {
      a_ = std::min(a_, -std::min(braking, limits_.max_braking));
    }
  }
  v_ = std::max(0.0, v_ + a_ * dt);
  s_ += v_ * dt;
  if (s_ >= traj.length() || (traj.length() - s_ < kCreepSpeed * dt && v_ <= kCreepSpeed)) {
    s_ = traj.length();  // arrived: at rest on the end point
    v_ = 0.0;
    a_ = 0.0;
  }
  if (v_ == 0.0 && a_ < 0.0) {
    a_ = 0.0;
  }
  const Trajectory::Point p = traj.at(s_);
  Reference r;
  r.p_W = p.p;
  r.v_W = v_ * p.tangent;
  r.a_W = a_ * p.tangent + v_ * v_ * p.curvature * p.normal;
  // Face along the path (when moving mostly horizontally), turning at most max_yaw_rate.
  double yaw = ref_.yaw;
  const double horizontal = p.tangent.head<2>().norm();
  if (v_ > 0.1 && horizontal > 0.3) {
    const double wanted = std::atan2(p.tangent.y(), p.tangent.x());
    const double step = std::clamp(geometry::wrapToPi(wanted - yaw), -limits_.max_yaw_rate * dt, limits_.max_yaw_rate * dt);
    yaw = geometry::wrapToPi(yaw + step);
    r.yaw_rate = step / dt;
  }
  r.yaw = yaw;
  ref_ = r;
  return r;
}

}  // namespace quad::control
