// SPDX-License-Identifier: BSD-3-Clause
#include "quad/control/trajectory_follower.hpp"

#include <algorithm>
#include <cmath>

#include "quad/geometry/so3.hpp"

namespace quad::control {

namespace {
/// [s] between the samples of the trajectory flown that a new one may also keep to, and how far
/// ahead (the turn from it onto a new path takes less).
constexpr double kFlownSampling = 0.05;
constexpr double kFlownAhead = 2.0;
/// [m/s] slower than this, the heading holds (the direction of motion means little).
constexpr double kHeadingSpeed = 0.3;
}  // namespace

trajectory::GeneratorConfig generatorConfig(const FollowerLimits& limits, const vehicle::VehicleParams& vehicle,
                                            double max_tilt, double gravity)
{
  trajectory::GeneratorConfig c;
  c.limits.max_speed = limits.max_speed;
  c.limits.max_acceleration = limits.max_acceleration;
  c.limits.max_jerk = limits.max_jerk;
  c.limits.max_tilt = limits.tilt_share * max_tilt;
  c.limits.gravity = gravity;
  const double top_thrust = vehicle::kRotorCount * vehicle.thrust_coefficient * vehicle.rotor_speed_max *
                            vehicle.rotor_speed_max / vehicle.mass;  // [m/s²]
  c.limits.max_thrust = std::max(limits.thrust_share * top_thrust, 1.05 * gravity);
  // Never ask for less than a third of the weight: descending that fast is falling.
  c.limits.min_thrust = gravity / 3.0;
  c.corridor = limits.corridor;
  c.corner_deviation = std::min(limits.corner_deviation, limits.corridor);
  return c;
}

namespace {
trajectory::GeneratorConfig braking(trajectory::GeneratorConfig c, double max_braking)
{
  const double scale = std::max(1.0, max_braking / c.limits.max_acceleration);
  c.limits.max_acceleration *= scale;
  c.limits.max_jerk *= scale;  // the same time to turn the acceleration round
  return c;
}
}  // namespace

TrajectoryFollower::TrajectoryFollower(FollowerLimits limits, const trajectory::GeneratorConfig& generator)
    : limits_(limits),
      generator_(generator),
      braking_(braking(generator, limits.max_braking)),
      trajectory_(trajectory::restingAt(Vector3::Zero(), 0.0))
{
}

void TrajectoryFollower::take(trajectory::Trajectory next, std::optional<std::uint32_t> version, double t)
{
  trajectory_ = std::move(next);
  version_ = version;
  ++taken_;
  progress_ = 0.0;
  last_t_ = t;
}

bool TrajectoryFollower::setPath(const std::vector<Vector3>& waypoints, std::uint32_t version, double t)
{
  if (waypoints.empty() || !std::isfinite(t) ||
      std::any_of(waypoints.begin(), waypoints.end(), [](const Vector3& w) { return !w.allFinite(); })) {
    ++refused_;
    last_refusal_ = "no waypoint, or one (or the time) not finite";
    return false;
  }
  const trajectory::State start = trajectory_.at(t);
  // Joined where the polyline passes nearest the reference: the path starts where the planner
  // expected the vehicle, which the reference is near but not on.
  std::size_t next = waypoints.size() > 1 ? 1 : 0;
  Vector3 join = waypoints.front();
  double best = (waypoints.front() - start.p).norm();
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Vector3 segment = waypoints[i + 1] - waypoints[i];
    const double length2 = segment.squaredNorm();
    const double u = length2 > 0.0 ? std::clamp((start.p - waypoints[i]).dot(segment) / length2, 0.0, 1.0) : 0.0;
    const Vector3 q = waypoints[i] + u * segment;
    if ((q - start.p).norm() < best) {
      best = (q - start.p).norm();
      join = q;
      next = i + 1;
    }
  }
  // Within the corridor of the path, the reference goes straight on to the next waypoint: that
  // hop keeps within the corridor of the path, where a detour by the nearest point would turn
  // the motion aside (a path planned during the climb, taken in the hover a few decimetres
  // above its start, dipped to it first). When no trajectory within the limits goes straight
  // on (a long first hop begun while the reference still accelerates aside), the path is
  // joined at the nearest point after all.
  std::vector<Vector3> rest(waypoints.begin() + static_cast<std::ptrdiff_t>(next), waypoints.end());
  std::vector<Vector3> joined{join};
  joined.insert(joined.end(), rest.begin(), rest.end());
  const bool straight_on = best <= generator_.config().corridor && next > 0;
  // The trajectory flown is space made for it too: a new one may keep to it while it turns
  // from the old motion to the new path.
  std::vector<Vector3> flown;
  if (start.v.norm() > 1e-3) {
    const double until = std::min(trajectory_.endTime(), t + kFlownAhead);
    for (double u = t; u < until; u += kFlownSampling) {
      flown.push_back(trajectory_.at(u).p);
    }
    flown.push_back(trajectory_.at(until).p);
  }
  const std::vector<std::vector<Vector3>> made = flown.size() > 1 ? std::vector<std::vector<Vector3>>{flown}
                                                                   : std::vector<std::vector<Vector3>>{};
  trajectory::GenerateResult r = generator_.generate(t, start, straight_on ? rest : joined, made);
  if (straight_on && r.status != trajectory::GenerateStatus::kOk) {
    r = generator_.generate(t, start, joined, made);
  }
  if (r.status != trajectory::GenerateStatus::kOk) {
    ++refused_;
    last_refusal_ = std::string(trajectory::toString(r.status)) + ": " + r.why;
    return false;
  }
  take(std::move(r.trajectory), version, t);
  return true;
}

void TrajectoryFollower::hold(const Vector3& p, double yaw, double t)
{
  take(trajectory::restingAt(p, t), std::nullopt, t);
  ref_ = Reference{p, Vector3::Zero(), Vector3::Zero(), yaw, 0.0, Vector3::Zero()};
}

void TrajectoryFollower::brake(double t)
{
  trajectory::GenerateResult r = braking_.stop(trajectory_, t);
  if (r.status != trajectory::GenerateStatus::kOk) {
    hold(ref_.p_W, ref_.yaw, t);  // nothing to brake along (an empty trajectory)
    return;
  }
  take(std::move(r.trajectory), std::nullopt, t);
}

bool TrajectoryFollower::finished(double t) const { return t >= trajectory_.endTime(); }

Reference TrajectoryFollower::step(double t)
{
  const trajectory::State s = trajectory_.at(t);
  const double dt = std::clamp(t - last_t_, 0.0, 0.1);
  progress_ += s.v.norm() * dt;
  last_t_ = t;
  Reference r;
  r.p_W = s.p;
  r.v_W = s.v;
  r.a_W = s.a;
  r.j_W = s.j;
  // Face along the motion (when mostly horizontal), turning at most max_yaw_rate.
  r.yaw = ref_.yaw;
  const double horizontal = s.v.head<2>().norm();
  if (horizontal > kHeadingSpeed && horizontal > 0.3 * s.v.norm() && dt > 0.0) {
    const double wanted = std::atan2(s.v.y(), s.v.x());
    const double step = std::clamp(geometry::wrapToPi(wanted - r.yaw), -limits_.max_yaw_rate * dt,
                                   limits_.max_yaw_rate * dt);
    r.yaw = geometry::wrapToPi(r.yaw + step);
    r.yaw_rate = step / dt;
  }
  ref_ = r;
  return r;
}

}  // namespace quad::control
