// SPDX-License-Identifier: BSD-3-Clause
#include "quad/report/figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "quad/launch/estimate_plot.hpp"
#include "quad/report/chart.hpp"

namespace quad::report {

namespace {

constexpr const char* kTruthColour = "#1f5fbf";
constexpr const char* kEstimateColour = "#27864a";
constexpr const char* kPathColour = "#e67e22";
constexpr const char* kObstacleColour = "#4d5656";
constexpr const char* kVoxelColour = "#8e44ad";

/// "CONTROL_FAILSAFE_LAND" -> "failsafe land".
std::string readable(const std::string& enumerator)
{
  std::string s = enumerator;
  for (const char* prefix : {"CONTROL_", "FAILSAFE_", "SIM_EVENT_", "PLAN_"}) {
    if (s.rfind(prefix, 0) == 0) {
      s = s.substr(std::string(prefix).size());
      break;
    }
  }
  for (char& c : s) {
    c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

std::string modeColour(const std::string& mode)
{
  static const std::array<std::pair<const char*, const char*>, 8> kColours{{{"CONTROL_DISARMED", "#95a5a6"},
                                                                             {"CONTROL_IDLE", "#7f8c8d"},
                                                                             {"CONTROL_TAKEOFF", "#2980b9"},
                                                                             {"CONTROL_MISSION", "#27ae60"},
                                                                             {"CONTROL_HOVER", "#f39c12"},
                                                                             {"CONTROL_LAND", "#16a085"},
                                                                             {"CONTROL_FAILSAFE_LAND", "#c0392b"},
                                                                             {"CONTROL_RETURN", "#8e44ad"}}};
  for (const auto& [name, colour] : kColours) {
    if (mode == name) {
      return colour;
    }
  }
  return "#34495e";
}

std::string eventColour(const FlightData::Event& e)
{
  if (e.kind == "SIM_EVENT_COLLISION") {
    return "#c0392b";
  }
  if (e.from_fault_tool || e.kind.find("FAULT") != std::string::npos) {
    return "#8e44ad";
  }
  return "#2c3e50";
}

/// A plane the views project onto: (x, y) for the top view, (distance along the start-goal
/// direction, z) for the side view.
struct Projection {
  bool top = true;
  Vector3 origin = Vector3::Zero();
  Vector3 along = Vector3::UnitX();  ///< horizontal unit direction of the side view

  Point operator()(const Vector3& p) const
  {
    if (top) {
      return {p.x(), p.y()};
    }
    return {(p - origin).head<2>().dot(along.head<2>()), p.z()};
  }
};

std::vector<Vector3> boxCorners(const world::Box& b)
{
  const double c = std::cos(b.yaw);
  const double s = std::sin(b.yaw);
  std::vector<Vector3> out;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      for (const double sz : {-1.0, 1.0}) {
        const double x = sx * b.size.x() / 2.0;
        const double y = sy * b.size.y() / 2.0;
        out.push_back(b.center + Vector3(c * x - s * y, s * x + c * y, sz * b.size.z() / 2.0));
      }
    }
  }
  return out;
}

void drawObstacle(PlanView& view, const world::Obstacle& o, const Projection& proj)
{
  constexpr double kOpacity = 0.5;
  switch (o.kind) {
    case world::Obstacle::Kind::kBox: {
      const auto corners = boxCorners(o.box);
      if (proj.top) {  // the footprint: corners 0, 2, 6, 4 go round the bottom face
        view.polygon({proj(corners[0]), proj(corners[2]), proj(corners[6]), proj(corners[4])}, kObstacleColour, kOpacity);
        return;
      }
      double lo = 1e300;
      double hi = -1e300;
      for (const auto& c : corners) {
        lo = std::min(lo, proj(c).first);
        hi = std::max(hi, proj(c).first);
      }
      const double z0 = o.box.center.z() - o.box.size.z() / 2.0;
      const double z1 = o.box.center.z() + o.box.size.z() / 2.0;
      view.polygon({{lo, z0}, {hi, z0}, {hi, z1}, {lo, z1}}, kObstacleColour, kOpacity);
      return;
    }
    case world::Obstacle::Kind::kCylinder: {
      const Vector3 axis(o.cylinder.x, o.cylinder.y, 0.0);
      if (proj.top) {
        view.circle(proj(axis), o.cylinder.radius, kObstacleColour, kOpacity);
        return;
      }
      const double s = proj(axis).first;
      const double r = o.cylinder.radius;
      view.polygon({{s - r, 0.0}, {s + r, 0.0}, {s + r, o.cylinder.height}, {s - r, o.cylinder.height}}, kObstacleColour,
                   kOpacity);
      return;
    }
    case world::Obstacle::Kind::kSphere:
      view.circle(proj(o.sphere.center), o.sphere.radius, kObstacleColour, kOpacity);
      return;
  }
}

/// Voxel centres projected, one per cell of the view's plane.
std::vector<Point> projectedVoxels(const std::vector<Vector3>& voxels, double resolution, const Projection& proj)
{
  std::set<std::pair<long, long>> seen;
  std::vector<Point> out;
  for (const auto& v : voxels) {
    const Point p = proj(v);
    const auto cell = [resolution](double u) { return static_cast<long>(std::floor(u / resolution)); };
    if (seen.emplace(cell(p.first), cell(p.second)).second) {
      out.push_back(p);
    }
  }
  return out;
}

std::vector<Point> projected(const std::vector<FlightData::State>& states, const Projection& proj)
{
  std::vector<Point> out;
  out.reserve(states.size());
  for (const auto& s : states) {
    out.push_back(proj(s.p_W));
  }
  return out;
}

/// The heights [m] the vehicle flew between (truth).
std::pair<double, double> flightBand(const FlightData& f)
{
  double z_lo = std::numeric_limits<double>::infinity();
  double z_hi = -z_lo;
  for (const auto& s : f.truth) {
    z_lo = std::min(z_lo, s.p_W.z());
    z_hi = std::max(z_hi, s.p_W.z());
  }
  return {z_lo, z_hi};
}

/// Whether p lies within a metre of the side view's vertical plane (what is farther would hide
/// the flight behind walls).
bool nearPlane(const Vector3& p, const Projection& proj)
{
  const Eigen::Vector2d off = (p - proj.origin).head<2>();
  return std::abs(off.x() * proj.along.y() - off.y() * proj.along.x()) <= 1.0;
}

/// The voxels of a scan that show what the vehicle flew past: from above, those between the
/// lowest and highest heights it flew at (floors and ceilings would hide the rest); from the
/// side, those within a metre of the vertical plane it is seen in.
std::vector<Vector3> mapVoxelsInView(const world::VoxelMap& m, const FlightData& f, const Projection& proj)
{
  const auto [z_lo, z_hi] = flightBand(f);
  const double half = 0.5 * m.resolution();
  std::vector<Vector3> out;
  for (const auto& i : m.occupiedVoxels()) {
    const Vector3 c = m.grid().centre(i);
    const bool in_view = proj.top ? c.z() + half > z_lo + 0.3 && c.z() - half < z_hi : nearPlane(c, proj);
    if (in_view) {
      out.push_back(c);
    }
  }
  return out;
}

/// The goal the vehicle flew to: the last one sent, else the world's.
std::optional<Vector3> finalGoal(const FlightData& f, const world::World* world)
{
  if (!f.goals.empty()) {
    return f.goals.back().p_W;
  }
  if (world != nullptr) {
    return world->goal();
  }
  return std::nullopt;
}

Figure view(const FlightData& f, const world::World* world, const Projection& proj)
{
  // Extent: the world's bounds, else what was flown and mapped, with a margin.
  Point lo{1e300, 1e300};
  Point hi{-1e300, -1e300};
  const auto grow = [&](const Point& p) {
    lo = {std::min(lo.first, p.first), std::min(lo.second, p.second)};
    hi = {std::max(hi.first, p.first), std::max(hi.second, p.second)};
  };
  if (world != nullptr) {
    const auto& b = world->bounds();
    for (const double x : {b.min.x(), b.max.x()}) {
      for (const double y : {b.min.y(), b.max.y()}) {
        for (const double z : {b.min.z(), b.max.z()}) {
          grow(proj(Vector3(x, y, z)));
        }
      }
    }
  } else {
    for (const auto& s : f.truth) {
      grow(proj(s.p_W));
    }
    for (const auto& v : f.occupied_W) {
      grow(proj(v));
    }
    if (const auto goal = finalGoal(f, world)) {
      grow(proj(*goal));
    }
    lo = {lo.first - 1.0, lo.second - 1.0};
    hi = {hi.first + 1.0, hi.second + 1.0};
  }
  PlanView v(proj.top ? "Top view: obstacles, the mapper's final map, planned paths and the flight"
                      : "Side view along the start-goal line",
             proj.top ? "x [m] (east)" : "distance along the start-goal line [m]", proj.top ? "y [m] (north)" : "z [m] (up)", lo,
             hi);
  if (f.map_resolution_m > 0.0) {
    // From above, the floor (and a ceiling) the camera saw would hide everything: the top view
    // leaves out the voxels of the ground's layer and those above the highest flown.
    const double ground = (world != nullptr ? world->supportHeight(world->start(), 0.0) : 0.0) + f.map_resolution_m;
    const double top = flightBand(f).second + f.map_resolution_m;
    std::vector<Vector3> shown;
    for (const auto& c : f.occupied_W) {
      if (proj.top ? c.z() > ground && c.z() <= top : nearPlane(c, proj)) {
        shown.push_back(c);
      }
    }
    v.squares(projectedVoxels(shown, f.map_resolution_m, proj), f.map_resolution_m, kVoxelColour, 0.45);
    v.legend(proj.top ? "mapped occupied voxels (from the ground to the highest flown)"
                      : "mapped occupied voxels (within 1 m of this plane)",
             kVoxelColour);
  }
  if (world != nullptr) {
    for (const auto& o : world->obstacles()) {
      drawObstacle(v, o, proj);
    }
    for (const auto& m : world->maps()) {
      v.squares(projectedVoxels(mapVoxelsInView(m, f, proj), m.resolution(), proj), m.resolution(), kObstacleColour, 0.55);
    }
    v.legend(world->maps().empty() ? "true obstacles"
             : proj.top             ? "true obstacles (scans: at the heights flown)"
                                    : "true obstacles (scans: within 1 m of this plane)",
             kObstacleColour);
  }
  std::size_t drawn = 0;
  for (const auto& p : f.paths) {
    if (p.status == "PLAN_OK" && p.waypoints_W.size() >= 2) {
      ++drawn;
    }
  }
  std::size_t k = 0;
  for (const auto& p : f.paths) {
    if (p.status != "PLAN_OK" || p.waypoints_W.size() < 2) {
      continue;
    }
    std::vector<Point> points;
    for (const auto& w : p.waypoints_W) {
      points.push_back(proj(w));
    }
    // Earlier paths fainter: the last one is the plan the vehicle finished on.
    v.polyline(points, kPathColour, 1.2, 0.15 + 0.6 * static_cast<double>(++k) / static_cast<double>(drawn));
  }
  if (drawn > 0) {
    v.legend(fmt::format("planned paths ({}, later darker)", drawn), kPathColour);
  }
  if (!f.estimate.empty()) {
    v.polyline(projected(f.estimate, proj), kEstimateColour, 1.5, 0.9);
    v.legend("estimated trajectory", kEstimateColour);
  }
  v.polyline(projected(f.truth, proj), kTruthColour, 2.2, 1.0);
  v.legend("flown trajectory (truth)", kTruthColour);
  v.marker(proj(f.truth.front().p_W), "start", "#ffffff");
  if (const auto goal = finalGoal(f, world)) {
    v.marker(proj(*goal), "goal", "#f1c40f");
  }
  for (const auto& e : f.events) {
    if (e.kind == "SIM_EVENT_COLLISION") {
      // the event's position is not kept: mark the trajectory's point nearest in time
      const auto at = std::lower_bound(f.truth.begin(), f.truth.end(), e.t_s,
                                       [](const FlightData::State& s, double t) { return s.t_s < t; });
      v.marker(proj((at == f.truth.end() ? f.truth.back() : *at).p_W), "collision", "#c0392b");
    }
  }
  if (proj.top) {
    return {"top_view.svg", "The world from above: true obstacles (grey), the voxels the mapper held occupied at the end (purple), every path the planner published (orange, later darker) and the trajectory flown.", v.svg()};
  }
  return {"side_view.svg", "The same, seen from the side along the line from the start to the goal: climbs, dips and the altitudes flown.", v.svg()};
}

Figure motion(const FlightData& f)
{
  Series altitude{{}, kTruthColour, "altitude (truth)"};
  Series speed{{}, kTruthColour, "speed (truth)"};
  Series distance{{}, kTruthColour, "distance to the goal"};
  std::size_t goal = 0;
  for (const auto& s : f.truth) {
    altitude.points.emplace_back(s.t_s, s.p_W.z());
    speed.points.emplace_back(s.t_s, s.v_W.norm());
    while (goal + 1 < f.goals.size() && f.goals[goal + 1].t_s <= s.t_s) {
      ++goal;
    }
    if (!f.goals.empty()) {
      distance.points.emplace_back(s.t_s, (s.p_W - f.goals[goal].p_W).norm());
    }
  }
  std::vector<Panel> panels{{"altitude [m]", {altitude}, 0.0, {}}, {"speed [m/s]", {speed}, 0.0, {}},
                            {"distance [m]", {distance}, 0.0, {}}};
  if (!f.estimate.empty()) {
    Series est{{}, kEstimateColour, "altitude (estimate)"};
    est.dash = "4,3";
    for (const auto& s : f.estimate) {
      est.points.emplace_back(s.t_s, s.p_W.z());
    }
    panels[0].series.push_back(est);
  }
  return {"motion.svg", "Altitude, speed and distance to the goal against sim time.",
          stackedChartSvg("Altitude, speed and distance to the goal", "sim time [s]", panels)};
}

Figure tracking(const FlightData& f)
{
  Series position{{}, "#c0392b", "position error (reference less actual)"};
  Series attitude{{}, "#8e44ad", "attitude error"};
  for (const auto& s : f.status) {
    position.points.emplace_back(s.t_s, s.position_error_m);
    attitude.points.emplace_back(s.t_s, s.attitude_error_deg);
  }
  return {"tracking.svg", "The controller's tracking error (quad/control/status) against sim time.",
          stackedChartSvg("Tracking error", "sim time [s]",
                          {{"position [m]", {position}, 0.0, {}}, {"attitude [deg]", {attitude}, 0.0, {}}})};
}

/// Runs of equal values as intervals (the last runs to `end`).
template <typename Sample, typename Value>
std::vector<Interval> runs(const std::vector<Sample>& samples, double end, Value value, const std::function<bool(const std::string&)>& shown,
                           const std::function<std::string(const std::string&)>& colour)
{
  std::vector<Interval> out;
  for (std::size_t k = 0; k < samples.size();) {
    const std::string v = value(samples[k]);
    std::size_t j = k + 1;
    while (j < samples.size() && value(samples[j]) == v) {
      ++j;
    }
    const double to = j < samples.size() ? samples[j].t_s : std::max(end, samples[k].t_s);
    if (shown(v)) {
      out.push_back({samples[k].t_s, to, readable(v), colour(v)});
    }
    k = j;
  }
  return out;
}

Figure timeline(const FlightData& f)
{
  const double end = f.t_last_s;
  Lane modes{"mode", {}, {}};
  modes.intervals = runs(f.status, end, [](const FlightData::Status& s) { return s.mode; }, [](const std::string&) { return true; },
                         modeColour);
  Lane failsafe{"failsafe reason", {}, {}};
  failsafe.intervals = runs(f.status, end, [](const FlightData::Status& s) { return s.failsafe; },
                            [](const std::string& v) { return v != "FAILSAFE_NONE"; },
                            [](const std::string&) { return std::string("#c0392b"); });
  Lane plan{"planner status", {}, {}};
  plan.intervals = runs(f.paths, end, [](const FlightData::Path& p) { return p.status; },
                        [](const std::string& v) { return v != "PLAN_OK"; }, [](const std::string&) { return std::string("#d35400"); });
  Lane events{"simulator events", {}, {}};
  Lane faults{"injected faults", {}, {}};
  for (const auto& e : f.events) {
    (e.from_fault_tool ? faults : events).instants.push_back({e.t_s, e.detail.empty() ? readable(e.kind) : e.detail, eventColour(e)});
  }
  std::vector<Lane> lanes{modes, failsafe, plan, events};
  if (!faults.instants.empty()) {
    lanes.push_back(faults);
  }
  return {"timeline.svg",
          "The controller's modes and failsafe reasons, the planner's failures, and the simulator's and fault tool's events "
          "(hover for times).",
          timelineSvg("Modes, failsafes and events", "sim time [s]", f.t_first_s, end, lanes)};
}

Figure replanning(const FlightData& f)
{
  Series time{{}, kPathColour, "replan time"};
  time.style = Series::Style::kDots;
  Series expansions{{}, "#2c3e50", "vertices expanded"};
  expansions.style = Series::Style::kDots;
  for (const auto& p : f.paths) {
    time.points.emplace_back(p.t_s, p.replan_time_s * 1e3);
    expansions.points.emplace_back(p.t_s, static_cast<double>(p.expansions));
  }
  Panel expanded{"expansions", {expansions}, {}, {}};
  expanded.log_scale = true;
  return {"replanning.svg", fmt::format("Each of the {} published paths: its compute time and the vertices its search expanded.", f.paths.size()),
          stackedChartSvg("Replanning", "sim time [s]", {{"replan time [ms]", {time}, 0.0, {}}, expanded})};
}

Figure rates(const FlightData& f)
{
  std::vector<Bar> bars;
  for (const auto& r : f.rates) {
    if (r.contract_hz) {
      bars.push_back({r.writers > 1 ? fmt::format("{} ({} writers)", r.topic, r.writers) : r.topic, r.rate_hz, r.contract_hz});
    }
  }
  return {"rates.svg", "Each periodic topic's rate, per writer, over the sim time its samples span (blue), against its contract's (red tick).",
          barChartSvg("Topic rates against their contracts", "rate [Hz] (sim time)", bars)};
}

}  // namespace

Figure reactionsFigure(const std::string& scenario, const std::vector<Reaction>& reactions)
{
  std::vector<Bar> bars;
  for (const auto& r : reactions) {
    // One that did not come is drawn at its bound's end, its label saying so.
    bars.push_back({r.measured_s ? r.label : r.label + " (not in time)", r.measured_s.value_or(r.within_s), r.within_s});
  }
  return {"reactions.svg",
          fmt::format("Scenario {}: each reaction's measured time (blue) against its bound (red tick); the table below "
                      "has every check.",
                      scenario),
          barChartSvg("Injected faults: the stack's reactions", "time after the fault [s]", bars, "measured", "bound")};
}

std::vector<Figure> flightFigures(const FlightData& flight, const world::World* world)
{
  std::vector<Figure> out;
  Projection top;
  out.push_back(view(flight, world, top));
  Projection side;
  side.top = false;
  side.origin = world != nullptr ? world->start() : flight.truth.front().p_W;
  if (const auto goal = finalGoal(flight, world); goal && (*goal - side.origin).head<2>().norm() > 1e-6) {
    side.along = Vector3((*goal - side.origin).x(), (*goal - side.origin).y(), 0.0).normalized();
  }
  out.push_back(view(flight, world, side));
  out.push_back(motion(flight));
  out.push_back(tracking(flight));
  out.push_back(timeline(flight));
  out.push_back(replanning(flight));
  out.push_back(rates(flight));
  if (!flight.estimate_error.empty()) {
    out.push_back({"estimate_error.svg", "The estimate's error against the truth, and the estimate's own 3-sigma bound.",
                   launch::estimateErrorSvg(flight.estimate_error, "The estimate against the truth")});
  }
  return out;
}

}  // namespace quad::report
