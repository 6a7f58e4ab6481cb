// SPDX-License-Identifier: BSD-3-Clause
#include "quad/trajectory/generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "quad/geometry/polyline.hpp"
#include "quad/trajectory/curve.hpp"
#include "quad/trajectory/min_snap.hpp"

namespace quad::trajectory {

namespace {

/// [m] between the samples of the curve's table.
constexpr double kCurveSpacing = 0.05;
/// The speed profile plans with these shares of the acceleration limit: along the curve (the
/// spline rounds the profile with some more), and across it in curves.
constexpr double kProfileAcceleration = 0.6;
constexpr double kProfileLateral = 0.7;
/// Braking from the start's speed may take up to this share of the acceleration limit, when the
/// curve is too short to brake on at the profile's share (a stop, or a path cut short).
constexpr double kHardestBraking = 0.85;
/// Samples may come this close to a limit: between two, a smooth piece rises a little more.
constexpr double kSampleMargin = 0.97;
/// How far (as a factor of the piece's duration, as Excess counts) the turn from a moving
/// start's motion onto the path may go past the limits: 5 % of the speed, 21 % of the
/// acceleration, 33 % of the jerk.
constexpr double kTransitionTolerance = 1.1;
/// Solves without getting nearer to the limits before a path is given up.
constexpr int kPatience = 6;
/// [s] a moving start is not held to the curve before this: the spline goes from its state to
/// the curve as smoothly as it can (the curve has neither its heading nor its curvature there).
constexpr double kFreeStart = 0.5;
/// [s] a piece of the spline lasts this long (longer when the trajectory would otherwise need
/// more than kMaxPieces).
constexpr double kPieceDuration = 0.2;
constexpr std::size_t kMaxPieces = 200;
/// [m/s] the slowest the time law moves (a cusp's speed limit is 0).
constexpr double kCreep = 0.05;
/// A stop's tries, hardest first: the share of the acceleration limit it brakes at, and how many
/// times the jerk limit's time its braking takes to ramp in.
constexpr std::array<std::pair<double, double>, 8> kStopSchedule{
    {{kHardestBraking, 1.05}, {kHardestBraking, 1.6}, {0.7, 1.05}, {0.7, 1.6}, {0.55, 1.6}, {0.55, 2.5}, {0.4, 2.5},
     {0.3, 4.0}}};
/// [m] a path shorter than this, from rest, is one straight hop (hop()), too short for a time
/// law to resolve; [s] the shortest hop.
constexpr double kShortHop = 0.3;
constexpr double kMinHopDuration = 0.2;
/// A moving start faster than this [m/s] whose velocity is more than kLeadInAngle [rad] off the
/// path's way goes on along it for kLeadInTime [s] before it joins the path (leadIn()).
constexpr double kLeadInSpeed = 0.3;
constexpr double kLeadInAngle = 0.05;
constexpr double kLeadInTime = 0.3;
/// [s] between the samples of the curve a stop brakes along (its corridor).
constexpr double kStopSampling = 0.02;
/// A stop may pass the speed limit (or the speed it brakes from, if faster) by this factor: its
/// spline, through points of the curve ahead at the braking's times, overshoots the time law
/// by a few per cent where the braking ramps in, and a stop refused for that flies on instead.
constexpr double kStopSpeedSlack = 1.05;

/// The time law along the curve: a speed at each of its samples.
struct Law {
  std::vector<double> cap;    ///< [m/s] the most a sample allows (the start's speed at the start)
  std::vector<double> accel;  ///< [m/s²] speeding up or braking into each sample
  std::vector<double> speed;  ///< [m/s] from the passes
};

/// The start carried on at its own acceleration along the curve for the smoothing window
/// (see knotsOf): where the profile takes over, and at what speed.
struct Lead {
  double duration = 0.0;  ///< [s]
  double speed = 0.0;     ///< [m/s] at its end
  double arc = 0.0;       ///< [m] covered
};

Lead leadOf(double speed, double accel, double duration, double length)
{
  Lead lead;
  lead.duration = duration;
  if (accel < 0.0 && speed + accel * duration < 0.0) {
    lead.duration = speed / -accel;  // at rest before the window is out
  }
  // Never more than half the curve: the profile must have room to stop on.
  for (int k = 0; k < 40 && speed * lead.duration + 0.5 * accel * lead.duration * lead.duration > 0.5 * length; ++k) {
    lead.duration *= 0.8;
  }
  lead.speed = std::max(0.0, speed + accel * lead.duration);
  lead.arc = std::max(0.0, speed * lead.duration + 0.5 * accel * lead.duration * lead.duration);
  return lead;
}

/// The points of the curve: `points` (the start and the path), but a moving start whose motion
/// points off the path's way first goes on along its velocity for kLeadInTime, and joins the
/// path kLeadInTime at its speed past where the path passes nearest that point (a path vertex
/// nearer than half that is the join): a curve along the path from the start would have to
/// turn the velocity at once. The corridor then holds the lead-in only where the caller's free
/// space (the trajectory flown, ahead) does.
std::vector<Vector3> leadIn(const State& start, const std::vector<Vector3>& points)
{
  const double speed = start.v.norm();
  if (speed < kLeadInSpeed || points.size() < 2) {
    return points;
  }
  const Vector3 heading = start.v / speed;
  const double step = kLeadInTime * speed;
  const Vector3 lead = start.p + heading * step;
  const double join = geometry::nearestArcLength(points, lead) + step;
  if (join >= geometry::polylineLength(points)) {
    return points;  // a path too short to join ahead: flown as it is (or found infeasible)
  }
  const Vector3 way = geometry::pointAlong(points, join + 0.1 * step) - geometry::pointAlong(points, join);
  if (way.norm() > 1e-9 && way.normalized().dot(heading) > std::cos(kLeadInAngle)) {
    return points;  // the path goes the velocity's way already
  }
  std::vector<Vector3> out{start.p, lead};
  double walked = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    walked += (points[i] - points[i - 1]).norm();
    if (walked <= join) {
      continue;
    }
    if (out.size() == 2 && walked - join > 0.5 * step) {
      out.push_back(geometry::pointAlong(points, join));
    }
    out.push_back(points[i]);
  }
  return out;
}

/// The speeds: each at most its cap, changing by at most its acceleration, from the lead's
/// speed where it ends to rest at the end (forward and backward passes). When braking from the
/// lead's speed to rest on the curve left takes more than the profile's deceleration, it brakes
/// as hard as it takes, up to `hardest` [m/s²]. Returns the index of the sample where the lead ends.
std::size_t plan(const Curve& curve, const Lead& lead, double hardest, Law& law)
{
  const std::vector<double>& s = curve.arcLengths();
  const std::size_t n = s.size();
  const std::size_t first = std::min<std::size_t>(
      n - 1, static_cast<std::size_t>(std::lower_bound(s.begin(), s.end(), lead.arc) - s.begin()));
  std::vector<double>& v = law.speed;
  v = law.cap;
  for (std::size_t i = 0; i <= first; ++i) {
    v[i] = lead.speed;
  }
  std::vector<double> accel = law.accel;
  const double left = s.back() - s[first];
  if (left > 1e-9) {
    const double needed = 1.15 * lead.speed * lead.speed / (2.0 * left);
    for (std::size_t i = first + 1; i < n; ++i) {
      accel[i] = std::max(accel[i], std::min(hardest, needed));
    }
  }
  for (std::size_t i = first + 1; i < n; ++i) {
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * accel[i] * (s[i] - s[i - 1])));
  }
  v.back() = 0.0;
  for (std::size_t i = n - 1; i-- > first + 1;) {
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * accel[i + 1] * (s[i + 1] - s[i])));
  }
  return first;
}

/// `in` averaged over 2 half + 1 samples centred on each, twice (zero beyond its ends): a
/// speed whose acceleration stepped then ramps, and its jerk ramps too.
std::vector<double> averagedTwice(const std::vector<double>& in, int half)
{
  const auto once = [half](const std::vector<double>& x) {
    std::vector<double> out(x.size(), 0.0);
    const auto w = static_cast<std::ptrdiff_t>(half);
    const auto size = static_cast<std::ptrdiff_t>(x.size());
    double sum = 0.0;
    for (std::ptrdiff_t k = -w; k < size + w; ++k) {
      sum += k + w < size ? x[static_cast<std::size_t>(k + w)] : 0.0;
      sum -= k - w - 1 >= 0 ? x[static_cast<std::size_t>(k - w - 1)] : 0.0;
      if (k >= 0 && k < size) {
        out[static_cast<std::size_t>(k)] = sum / static_cast<double>(2 * w + 1);
      }
    }
    return out;
  };
  return once(once(in));
}

/// The knots of the spline: where the smoothed time law is every piece's duration.
struct Knots {
  std::vector<Vector3> through;      ///< between the pieces
  std::vector<double> durations;     ///< [s] a piece
  std::vector<double> arc;           ///< [m] of the curve at each piece's start, and at the end
};

/// The time law, smoothed, sampled at equal times.
///
/// The profile's acceleration steps from one value to another; a spline made to pass points on
/// that law rings around each step (its derivatives are continuous, the law's are not), with
/// speeds past the limits for several pieces around. The law's speed averaged over a window of
/// `window` [s] has an acceleration that ramps instead (by at most its step over the window: a
/// jerk limit), and a spline through points of it at equal times follows it closely. For a
/// window before and after the start the law goes on at the start's speed and acceleration along
/// the curve (the lead), so that the averages start with them as the spline does.
Knots knotsOf(const Curve& curve, const Law& law, std::size_t first, double start_speed, double start_accel,
              const Lead& lead, double window, double free_until)
{
  const std::vector<double>& s = curve.arcLengths();
  const std::size_t n = s.size();
  std::vector<double> t(n, lead.duration);
  for (std::size_t i = first + 1; i < n; ++i) {
    t[i] = t[i - 1] + 2.0 * (s[i] - s[i - 1]) / std::max(law.speed[i - 1] + law.speed[i], 2.0 * kCreep);
  }
  const double total = t.back();
  const double dt = std::clamp(total / 2000.0, 1e-4, 0.005);
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * window / dt)));
  const int steps = static_cast<int>(std::ceil(total / dt));
  const auto gridSpeed = [&](int k) {
    const double time = k * dt;
    if (time < lead.duration) {
      return std::max(0.0, start_speed + start_accel * time);
    }
    if (time >= total) {
      return 0.0;
    }
    const auto from = t.begin() + static_cast<std::ptrdiff_t>(first);
    const std::size_t i = std::max<std::size_t>(
        first + 1, static_cast<std::size_t>(std::upper_bound(from, t.end(), time) - t.begin()));
    if (i >= n) {
      return 0.0;
    }
    const double u = (time - t[i - 1]) / std::max(t[i] - t[i - 1], 1e-12);
    return law.speed[i - 1] + u * (law.speed[i] - law.speed[i - 1]);
  };
  // The law's speed on a grid from −2 half to steps + 2 half, averaged twice over the window
  // centred on each time: once, the acceleration ramps instead of stepping; twice, the jerk
  // does too, so that the law starts and ends with no jerk, as the spline does.
  const int margin = 2 * half;
  std::vector<double> raw;
  for (int k = -margin; k <= steps + margin; ++k) {
    raw.push_back(gridSpeed(k));
  }
  const std::vector<double> smooth = averagedTwice(raw, half);
  // Integrated into arc length from t = 0 (grid index `margin`).
  std::vector<double> walked{0.0};
  for (std::size_t k = static_cast<std::size_t>(margin) + 1; k < smooth.size(); ++k) {
    walked.push_back(walked.back() + 0.5 * (smooth[k - 1] + smooth[k]) * dt);
  }
  // The window shifts a little of the start's speed into the law: its arc length is scaled back
  // onto the curve's.
  const double scale = walked.back() > 0.0 ? curve.length() / walked.back() : 1.0;
  const double end = static_cast<double>(walked.size() - 1) * dt;
  const double interval = std::max(kPieceDuration, end / static_cast<double>(kMaxPieces));
  const int pieces = std::max(1, static_cast<int>(std::lround(end / interval)));
  const double duration = end / pieces;
  Knots knots;
  knots.arc.push_back(0.0);
  double last = 0.0;
  for (int k = 1; k < pieces; ++k) {
    const double time = k * duration;
    if (time < free_until) {
      continue;
    }
    knots.durations.push_back(time - last);
    last = time;
    const std::size_t j = std::min(walked.size() - 2, static_cast<std::size_t>(time / dt));
    const double u = time / dt - static_cast<double>(j);
    const double arc = scale * (walked[j] + u * (walked[j + 1] - walked[j]));
    knots.through.push_back(curve.at(arc).p);
    knots.arc.push_back(arc);
  }
  knots.arc.push_back(curve.length());
  knots.durations.push_back(end - last);
  return knots;
}

/// How far a sampled state is past the limits, each as the factor its piece's duration would
/// have to grow by (1 or less: within them): `speed` its speed over the limit; its
/// acceleration (and so thrust and tilt) under a square root and its jerk under a cube root,
/// counted as `lateral` where the acceleration is mostly across the motion (a curve: only a
/// lower speed helps) and as `longitudinal` where it is along it (speeding up or braking: a
/// gentler acceleration helps).
struct Excess {
  double speed = 1.0;
  double lateral = 1.0;
  double longitudinal = 1.0;

  void include(const Excess& e)
  {
    speed = std::max(speed, e.speed);
    lateral = std::max(lateral, e.lateral);
    longitudinal = std::max(longitudinal, e.longitudinal);
  }
  bool within() const { return speed <= 1.0 && lateral <= 1.0 && longitudinal <= 1.0; }
};

Excess overLimits(const State& s, const Limits& limits, const Limits& first)
{
  const Vector3 thrust = s.a + limits.gravity * Vector3::UnitZ();
  const double f = thrust.norm();
  Excess e;
  e.speed = s.v.norm() / (kSampleMargin * first.max_speed);
  double effort = std::max(std::sqrt(s.a.norm() / (kSampleMargin * first.max_acceleration)),
                           std::cbrt(s.j.norm() / (kSampleMargin * first.max_jerk)));
  if (thrust.z() <= 0.0) {
    effort = std::max(effort, 2.0);  // thrust pointing down: far past any tilt
  } else {
    const double tan_tilt = thrust.head<2>().norm() / thrust.z();
    effort = std::max(effort, std::sqrt(tan_tilt / (kSampleMargin * std::tan(first.max_tilt))));
    effort = std::max(effort, std::sqrt(std::max(0.0, f - limits.gravity) /
                                        (kSampleMargin * (first.max_thrust - limits.gravity))));
    effort = std::max(effort, std::sqrt(std::max(0.0, limits.gravity - f) /
                                        (kSampleMargin * (limits.gravity - first.min_thrust))));
  }
  const double speed = s.v.norm();
  const double along = speed > 1e-6 ? std::abs(s.a.dot(s.v)) / speed : s.a.norm();
  const bool across = (s.a.norm() * s.a.norm() - along * along) > along * along;
  (across ? e.lateral : e.longitudinal) = effort;
  return e;
}

/// [m] how far p is from every polyline of `free` (the nearest counts), or any distance up to
/// `enough` when it is at most that.
double deviation(const Vector3& p, const std::vector<std::vector<Vector3>>& free, double enough)
{
  // Within `enough` of one polyline it is within the corridor: the others need not be read
  // (the path, first, holds most samples; the trajectory flown is long).
  double best = std::numeric_limits<double>::infinity();
  for (const auto& polyline : free) {
    best = std::min(best, geometry::distanceToPolyline(polyline, p));
    if (best <= enough) {
      break;
    }
  }
  return best;
}

/// Each piece of a spline sampled against the limits and the corridor.
struct Judged {
  std::vector<Excess> excess;    ///< a piece
  std::vector<double> deviation; ///< [m] a piece: the farthest sample from what is free
  Excess worst;
  double worst_deviation = 0.0;
};

Judged judge(const std::vector<Piece>& pieces, const Limits& limits, const Limits& first,
             const std::vector<std::vector<Vector3>>& free, double corridor, int samples)
{
  Judged j;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const Piece& piece = pieces[i];
    Excess excess;
    double off = 0.0;
    for (int k = 1; k <= samples; ++k) {
      const State s = piece.at(piece.duration * k / samples);
      excess.include(overLimits(s, limits, i == 0 ? first : limits));
      off = std::max(off, deviation(s.p, free, corridor));
    }
    j.excess.push_back(excess);
    j.deviation.push_back(off);
    j.worst.include(excess);
    j.worst_deviation = std::max(j.worst_deviation, off);
  }
  return j;
}

/// The limits a trajectory from `start` is held to in its first piece: the configured ones, or
/// what the start already has when it is past them (the limits changed, a push).
Limits firstLimits(const Limits& limits, const State& start)
{
  Limits first = limits;
  const Vector3 thrust = start.a + first.gravity * Vector3::UnitZ();
  first.max_speed = std::max(first.max_speed, start.v.norm());
  first.max_acceleration = std::max(first.max_acceleration, start.a.norm());
  first.max_jerk = std::max(first.max_jerk, start.j.norm());
  first.max_thrust = std::max(first.max_thrust, thrust.norm());
  first.min_thrust = std::min(first.min_thrust, thrust.norm());
  if (thrust.z() > 0.0) {
    first.max_tilt = std::max(first.max_tilt, std::atan2(thrust.head<2>().norm(), thrust.z()));
  }
  return first;
}

std::string describe(int solves, const Excess& worst, double worst_deviation, double corridor)
{
  return fmt::format("after {} solves a piece is still {:.2f} times too fast, needs {:.2f} times less effort "
                     "(acceleration, jerk, tilt, thrust) in a curve or {:.2f} times less along its way, or strays "
                     "{:.2f} m from the path (corridor {:.2f} m)",
                     solves, worst.speed, worst.lateral, worst.longitudinal, worst_deviation, corridor);
}

/// From rest at `from` to rest at `to` in one piece: the septic of min_snap.hpp's closed form,
/// whose speed, acceleration and jerk peak at 2.19, 7.51 and 52.5 times the distance over the
/// duration's first, second and third power; the duration is the shortest that keeps each
/// limit (the thrust and tilt of a hop this short are the weight's).
GenerateResult hop(double t0, const Vector3& from, const Vector3& to, const Limits& l)
{
  const double d = (to - from).norm();
  const double duration = std::max({kMinHopDuration, 1.05 * 35.0 / 16.0 * d / l.max_speed,
                                    1.05 * std::sqrt(7.51 * d / l.max_acceleration),
                                    1.05 * std::cbrt(52.5 * d / l.max_jerk)});
  GenerateResult r;
  r.iterations = 1;
  const auto pieces = minimumSnap(State{from}, {}, State{to}, {duration});
  if (!pieces) {
    r.status = GenerateStatus::kInfeasible;
    r.why = "the hop's system is singular";
    return r;
  }
  r.status = GenerateStatus::kOk;
  r.trajectory = Trajectory(t0, *pieces);
  return r;
}

bool finite(const State& s) { return s.p.allFinite() && s.v.allFinite() && s.a.allFinite() && s.j.allFinite(); }

void require(bool ok, const std::string& what, double value)
{
  if (!ok) {
    throw std::invalid_argument(fmt::format("trajectory generator: {} = {}: {}", what, value,
                                            "must be positive and finite (see the generator's limits)"));
  }
}

}  // namespace

std::string_view toString(GenerateStatus status)
{
  switch (status) {
    case GenerateStatus::kOk:
      return "ok";
    case GenerateStatus::kInvalidInput:
      return "invalid input";
    case GenerateStatus::kInfeasible:
      return "infeasible";
  }
  return "?";
}

Extremes extremes(const Trajectory& trajectory, double gravity, int samples_per_piece)
{
  Extremes e;
  e.min_thrust = std::numeric_limits<double>::infinity();
  for (const Piece& piece : trajectory.pieces()) {
    for (int k = 0; k <= samples_per_piece; ++k) {
      const State s = piece.at(piece.duration * k / samples_per_piece);
      const Vector3 thrust = s.a + gravity * Vector3::UnitZ();
      e.speed = std::max(e.speed, s.v.norm());
      e.acceleration = std::max(e.acceleration, s.a.norm());
      e.jerk = std::max(e.jerk, s.j.norm());
      e.tilt = std::max(e.tilt, std::atan2(thrust.head<2>().norm(), thrust.z()));
      e.max_thrust = std::max(e.max_thrust, thrust.norm());
      e.min_thrust = std::min(e.min_thrust, thrust.norm());
    }
  }
  return e;
}

Generator::Generator(GeneratorConfig config) : config_(config)
{
  const Limits& l = config_.limits;
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  require(positive(l.max_speed), "max_speed", l.max_speed);
  require(positive(l.max_acceleration), "max_acceleration", l.max_acceleration);
  require(positive(l.max_jerk), "max_jerk", l.max_jerk);
  require(positive(l.max_tilt) && l.max_tilt < 1.5, "max_tilt (below pi/2)", l.max_tilt);
  require(positive(l.gravity), "gravity", l.gravity);
  require(positive(l.max_thrust) && l.max_thrust > l.gravity, "max_thrust (above gravity)", l.max_thrust);
  require(l.min_thrust >= 0.0 && l.min_thrust < l.gravity, "min_thrust (in [0, gravity))", l.min_thrust);
  require(positive(config_.corridor), "corridor", config_.corridor);
  require(positive(config_.corner_deviation) && config_.corner_deviation <= config_.corridor,
          "corner_deviation (at most the corridor)", config_.corner_deviation);
  require(config_.max_iterations >= 1, "max_iterations", config_.max_iterations);
  require(config_.samples_per_piece >= 1, "samples_per_piece", config_.samples_per_piece);
}

GenerateResult Generator::generate(double t0, const State& start, const std::vector<Vector3>& path,
                                   const std::vector<std::vector<Vector3>>& also_free) const
{
  GenerateResult result;
  const bool path_finite = std::all_of(path.begin(), path.end(), [](const Vector3& w) { return w.allFinite(); });
  if (path.empty() || !path_finite || !finite(start) || !std::isfinite(t0)) {
    result.why = "no path, or a point, the start or its time not finite";
    return result;
  }
  std::vector<Vector3> points{start.p};
  points.insert(points.end(), path.begin(), path.end());
  const Limits& limits = config_.limits;
  // The time law's smoothing: its acceleration ramps over this window, at half the jerk limit.
  const double window = kProfileAcceleration * limits.max_acceleration / (0.5 * limits.max_jerk);
  const double start_speed = start.v.norm();
  const double start_accel = start_speed > 1e-6 ? start.a.dot(start.v) / start_speed : 0.0;
  const Lead lead = leadOf(start_speed, start_accel, window, geometry::polylineLength(points));
  const Curve curve(leadIn(start, points), config_.corner_deviation, kCurveSpacing);
  if (curve.length() < 1e-3 && start.v.norm() < 1e-6 && start.a.norm() < 1e-6) {
    result.status = GenerateStatus::kOk;
    result.trajectory = restingAt(curve.at(curve.length()).p, t0);  // at rest where it is to be
    return result;
  }
  std::vector<std::vector<Vector3>> free{points};
  free.insert(free.end(), also_free.begin(), also_free.end());
  const bool at_rest = start.v.norm() < 1e-3 && start.a.norm() < 1e-3 && start.j.norm() < 1e-3;
  if (at_rest && curve.length() < kShortHop) {
    const std::vector<Vector3> chord{start.p, curve.at(curve.length()).p};
    const bool straight = std::all_of(points.begin(), points.end(), [&](const Vector3& p) {
      return geometry::distanceToPolyline(chord, p) <= config_.corridor;
    });
    if (straight) {
      return hop(t0, chord.front(), chord.back(), config_.limits);
    }
  }
  Law law;
  for (const Curve::Sample& c : curve.samples()) {
    law.cap.push_back(c.curvature > 1e-9 ? std::min(limits.max_speed,
                                                    std::sqrt(kProfileLateral * limits.max_acceleration / c.curvature))
                                         : limits.max_speed);
  }
  law.accel.assign(law.cap.size(), kProfileAcceleration * limits.max_acceleration);
  const Limits first = firstLimits(limits, start);
  const State end{curve.at(curve.length()).p, Vector3::Zero(), Vector3::Zero(), Vector3::Zero()};
  const std::vector<double>& arc = curve.arcLengths();
  const int samples = config_.samples_per_piece;
  double best = std::numeric_limits<double>::infinity();
  int best_at = 0;
  for (int iteration = 1; iteration <= config_.max_iterations; ++iteration) {
    result.iterations = iteration;
    const std::size_t first_sample = plan(curve, lead, kHardestBraking * limits.max_acceleration, law);
    const Knots knots = knotsOf(curve, law, first_sample, start_speed, start_accel, lead, window,
                                start_speed > 0.1 ? kFreeStart : 0.0);
    const auto pieces = minimumSnap(start, knots.through, end, knots.durations);
    if (!pieces) {
      result.status = GenerateStatus::kInfeasible;
      result.why = "the spline's system is singular";
      return result;
    }
    // Each piece sampled; where one breaks a limit or strays, the law is lowered over the part of
    // the curve it covers (and a window's worth around: the smoothing spreads the law), and the
    // spline solved again.
    const Judged judged = judge(*pieces, limits, first, free, config_.corridor, samples);
    bool within = true;
    bool lowered = false;
    const Law before = law;
    for (std::size_t i = 0; i < pieces->size(); ++i) {
      const Excess& excess = judged.excess[i];
      // Lateral acceleration goes with the square of the speed, and so does the effort's square.
      // An effort along the way is eased by a gentler acceleration, and a little by a lower
      // speed (the spline's own swings grow with it).
      double slower = std::max({excess.speed, excess.lateral, std::sqrt(excess.longitudinal)});
      if (judged.deviation[i] > config_.corridor) {
        slower = std::max(slower, 1.2);  // straying between its points: slower, with them closer
      }
      if (slower <= 1.0 && excess.longitudinal <= 1.0) {
        continue;
      }
      // The turn from the start's motion onto the path: a moving start is left free there, and
      // may ask a little more than the limits for that transient (the limits are a mission's
      // choice, shares of what the vehicle can: follower.thrust_share, tilt_share).
      const bool transition = i == 0 || knots.arc[i] < lead.arc;
      if (transition && judged.deviation[i] <= config_.corridor &&
          std::max({excess.speed, excess.lateral, excess.longitudinal}) <= kTransitionTolerance) {
        continue;
      }
      within = false;
      if (transition) {
        continue;  // the start's own motion: nothing to lower there (see below)
      }
      lowered = true;
      const double margin = limits.max_speed * window;
      const auto from = std::lower_bound(arc.begin(), arc.end(), knots.arc[i] - margin) - arc.begin();
      const auto to = std::upper_bound(arc.begin(), arc.end(), knots.arc[i + 1] + margin) - arc.begin();
      for (auto j = static_cast<std::size_t>(from); j < static_cast<std::size_t>(to); ++j) {
        if (slower > 1.0) {
          law.cap[j] = std::min(law.cap[j], std::max(before.speed[j], kCreep) / (1.02 * slower));
        }
        if (excess.longitudinal > 1.0) {
          law.accel[j] = std::min(law.accel[j], before.accel[j] / (1.02 * excess.longitudinal * excess.longitudinal));
        }
      }
    }
    if (within) {
      result.status = GenerateStatus::kOk;
      result.trajectory = Trajectory(t0, *pieces);
      return result;
    }
    result.why = describe(iteration, judged.worst, judged.worst_deviation, config_.corridor);
    if (!lowered) {
      break;  // only the start's own motion breaks them: it cannot be flown from this state
    }
    // How far from feasible, as one number; a law lowered for kPatience solves without getting
    // nearer will not get there.
    const double distance = std::max({judged.worst.speed, judged.worst.lateral, judged.worst.longitudinal,
                                      judged.worst_deviation / config_.corridor});
    if (distance < 0.99 * best) {
      best = distance;
      best_at = iteration;
    } else if (iteration - best_at >= kPatience) {
      break;
    }
  }
  result.status = GenerateStatus::kInfeasible;
  return result;
}

GenerateResult Generator::stop(const Trajectory& current, double t) const
{
  GenerateResult result;
  if (current.empty() || !std::isfinite(t)) {
    result.why = "no trajectory to stop along, or the time not finite";
    return result;
  }
  const State s = current.at(t);
  const double speed = s.v.norm();
  if (t >= current.endTime() || (speed < 1e-3 && s.a.norm() < 1e-3)) {
    result.status = GenerateStatus::kOk;
    result.trajectory = restingAt(s.p, t);
    return result;
  }
  // The curve ahead, as `current` would fly it: the corridor.
  std::vector<std::vector<Vector3>> free(1);
  for (double u = t; u < current.endTime(); u += kStopSampling) {
    free.front().push_back(current.at(u).p);
  }
  free.front().push_back(current.at(current.endTime()).p);
  Limits limits = config_.limits;
  limits.max_speed = kStopSpeedSlack * std::max(limits.max_speed, speed);
  const Limits first = firstLimits(limits, s);
  // Along the same curve, slower: flown at σ(τ) of its own time, σ' from 1 down to 0. σ' holds
  // at 1 for a window, then falls at the rate that brakes the start's speed at a share of the
  // acceleration limit, averaged twice over the window (as the generator's time law, so that
  // the braking ramps in and out, here at about the jerk limit: a stop is in a hurry); the
  // spline then passes the points of `current` at σ of equal times. The hardest share first;
  // gentler ones while a limit is broken.
  for (const auto& [share, ease] : kStopSchedule) {
    ++result.iterations;
    // The braking's ramp turns the acceleration from the start's, along the motion, to the
    // braking's: at the jerk limit it takes this long (times `ease`).
    const double turn = share * limits.max_acceleration + std::max(0.0, s.a.dot(s.v) / speed);
    const double window = ease * turn / limits.max_jerk;
    const double rate = share * limits.max_acceleration / std::max(speed, 1e-3);  // [1/s]
    const double dt = 0.002;
    const int half = std::max(1, static_cast<int>(std::lround(0.5 * window / dt)));
    const int steps = static_cast<int>(std::ceil((window + 1.0 / rate) / dt));
    std::vector<double> raw;
    for (int k = -2 * half; k <= steps + 2 * half; ++k) {
      const double time = k * dt;
      raw.push_back(time < window ? 1.0 : std::max(0.0, 1.0 - rate * (time - window)));
    }
    const std::vector<double> rate_of_sigma = averagedTwice(raw, half);
    std::vector<double> sigma{0.0};  // from the grid's t = 0
    for (std::size_t k = static_cast<std::size_t>(2 * half) + 1; k < rate_of_sigma.size(); ++k) {
      sigma.push_back(sigma.back() + 0.5 * (rate_of_sigma[k - 1] + rate_of_sigma[k]) * dt);
    }
    const double total = static_cast<double>(sigma.size() - 1) * dt;
    if (t + sigma.back() >= current.endTime()) {
      break;  // no sooner at rest than `current` itself
    }
    const int pieces = std::max(1, static_cast<int>(std::lround(total / kPieceDuration)));
    const double duration = total / pieces;
    std::vector<Vector3> through;
    std::vector<double> durations;
    double last = 0.0;
    for (int k = 1; k < pieces; ++k) {
      const double time = k * duration;
      if (time < kFreeStart) {
        continue;
      }
      const std::size_t j = std::min(sigma.size() - 1, static_cast<std::size_t>(std::lround(time / dt)));
      through.push_back(current.at(t + sigma[j]).p);
      durations.push_back(time - last);
      last = time;
    }
    durations.push_back(total - last);
    const State end{current.at(t + sigma.back()).p, Vector3::Zero(), Vector3::Zero(), Vector3::Zero()};
    const auto spline = minimumSnap(s, through, end, durations);
    if (!spline) {
      continue;
    }
    const Judged judged = judge(*spline, limits, first, free, config_.corridor, config_.samples_per_piece);
    if (judged.worst.within() && judged.worst_deviation <= config_.corridor) {
      result.status = GenerateStatus::kOk;
      result.trajectory = Trajectory(t, *spline);
      result.why.clear();
      return result;
    }
    result.why = describe(result.iterations, judged.worst, judged.worst_deviation, config_.corridor);
  }
  // No braking within the limits comes to rest sooner: the trajectory itself, which ends at rest.
  result.status = GenerateStatus::kOk;
  result.trajectory = current;
  result.why = "no braking within the limits stops sooner than the trajectory flown: flown to its end";
  return result;
}

}  // namespace quad::trajectory
