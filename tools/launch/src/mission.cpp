// SPDX-License-Identifier: BSD-3-Clause
#include "quad/launch/mission.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace quad::launch {

MissionTracker::MissionTracker(Mission mission, const world::World& world, double radius)
    : mission_(std::move(mission)),
      world_(world),
      radius_(radius),
      goal_(world.goal()),
      min_clearance_(std::numeric_limits<double>::infinity())
{
}

void MissionTracker::onState(double t, const Eigen::Vector3d& p)
{
  // States stamped up to the mission's end count however late they come beside the mode that
  // ended it; later ones not.
  if (!p.allFinite() || (finished_ && t > end_t_)) {
    return;
  }
  t_ = std::max(t_, t);
  if (last_p_) {
    length_ += (p - *last_p_).norm();
    if (t > last_t_) {
      top_speed_ = std::max(top_speed_, (p - *last_p_).norm() / (t - last_t_));
    }
  }
  last_p_ = p;
  last_t_ = t;
  // the length at the mission's start, from the states stamped up to it, however late they
  // come beside its mode
  constexpr std::size_t kRecentStates = 4096;
  recent_lengths_.emplace_back(t, length_);
  if (recent_lengths_.size() > kRecentStates) {
    recent_lengths_.pop_front();
  }
  if (mission_t_ && t <= *mission_t_) {
    mission_length_ = length_;
  }
  // only a solid nearer than the closest approach so far can change it
  if (const auto near = world_.nearest(p, radius_, min_clearance_ + radius_)) {
    min_clearance_ = std::min(min_clearance_, near->distance - radius_);
  }
  if (finished_) {
    return;
  }
  const double to_goal = (p - goal_).norm();
  if (!goal_reached_ && to_goal <= mission_.tolerance_m) {
    goal_reached_ = true;
    goal_t_ = t;
    goal_length_ = length_;
    progress_.push_back(fmt::format("t = {:.1f} s: goal reached ({:.2f} m from it)", t, to_goal));
    if (!mission_.land) {
      finishAtGoal(t, "reached the goal");
    }
  }
  if (t >= next_progress_t_) {
    progress_.push_back(fmt::format("t = {:.0f} s: at ({:.1f}, {:.1f}, {:.1f}), {:.1f} m to the goal, {} paths, mode {}",
                                    t, p.x(), p.y(), p.z(), to_goal, path_times_.size(), mode_.empty() ? "?" : mode_));
    next_progress_t_ += 10.0;
  }
  if (!finished_ && t >= mission_.timeout_s) {
    finish(t, MissionEnd::kFailed, fmt::format("timed out after {:.0f} s of sim time, {:.2f} m from the goal", t, to_goal),
           no_path_.empty() ? "timed out" : "timed out; " + no_path_);
  }
}

void MissionTracker::onMode(double t, const std::string& mode, const std::string& ended_by)
{
  if (!ended_by.empty() && ended_by_.empty() && !finished_) {
    ended_by_ = ended_by;
    ended_by_t_ = t;
    progress_.push_back(fmt::format("t = {:.1f} s: {}", t, ended_by));
  }
  if (mode == mode_ || finished_) {
    return;
  }
  progress_.push_back(fmt::format("t = {:.1f} s: {} -> {}", t, mode_.empty() ? "start" : mode_, mode));
  modes_.push_back(fmt::format("{:.2f} {}", t, mode));
  mode_times_.emplace_back(t, mode);
  if (mode == "MISSION" && !mission_t_) {
    mission_t_ = t;
    mission_length_ = 0.0;
    for (auto it = recent_lengths_.rbegin(); it != recent_lengths_.rend(); ++it) {
      if (it->first <= t) {
        mission_length_ = it->second;
        break;
      }
    }
  }
  const bool was_landing = mode_ == "LAND" || mode_ == "FAILSAFE_LAND";
  // The controller gives up on a goal the planner calls unreachable by returning (or
  // landing); a path the planner finds again while it does so does not undo that.
  if ((mode == "RETURN" || mode == "LAND") && gave_up_.empty()) {
    gave_up_ = no_path_;
  }
  mode_ = mode;
  if (was_landing && mode == "IDLE") {
    const double to_goal = last_p_ ? (last_p_->head<2>() - goal_.head<2>()).norm() : 0.0;
    if (goal_reached_ && to_goal <= mission_.tolerance_m + 0.5) {
      finishAtGoal(t, "landed at the goal");
    } else if (!ended_by_.empty()) {
      const std::string why = fmt::format("{} at t = {:.1f} s", ended_by_, ended_by_t_);
      finish(t, MissionEnd::kFailed, fmt::format("landed {:.2f} m from the goal: {}", to_goal, why), why);
    } else if (const std::string& why = gave_up_.empty() ? no_path_ : gave_up_; !why.empty()) {
      finish(t, MissionEnd::kNoPath, fmt::format("landed {:.2f} m from the goal: {}", to_goal, why), why);
    } else {
      finish(t, MissionEnd::kFailed, fmt::format("landed {:.2f} m from the goal", to_goal), "landed short of the goal");
    }
  }
}

void MissionTracker::onPath(double t, std::uint32_t version, const std::string& no_path)
{
  if (version != last_version_) {
    last_version_ = version;
    path_times_.push_back(t);  // counted up to the mission's end, however late the stack is stopped
  }
  if (finished_) {
    return;
  }
  if (no_path != no_path_) {
    progress_.push_back(no_path.empty() ? fmt::format("t = {:.1f} s: the planner has a path again", t_)
                                        : fmt::format("t = {:.1f} s: {}", t_, no_path));
  }
  no_path_ = no_path;
}

void MissionTracker::onTrajectory(double t, double depth_t)
{
  if (std::isfinite(t) && std::isfinite(depth_t) && t >= depth_t) {
    depth_latencies_.emplace_back(t, t - depth_t);  // judged by the mode at t (summary)
  }
}

void MissionTracker::onCollision(double t)
{
  ++collisions_;
  progress_.push_back(fmt::format("t = {:.1f} s: COLLISION", t));
}

void MissionTracker::onCrash(double t, const std::string& detail)
{
  progress_.push_back(fmt::format("t = {:.1f} s: {}", t, detail));
  if (!finished_) {
    finish(t, MissionEnd::kCrashed, detail, detail);
  }
}

namespace {
/// A count since a module's start, heard in samples that may come out of order: the largest.
void keepNewest(std::optional<std::uint64_t>& count, std::uint64_t heard)
{
  count = std::max(count.value_or(0), heard);
}
/// A fleet's count: the vehicles' summed, unknown when no vehicle's was heard.
void addCount(std::optional<std::uint64_t>& sum, const std::optional<std::uint64_t>& vehicle)
{
  if (vehicle) {
    sum = sum.value_or(0) + *vehicle;
  }
}
/// The larger of two figures, either of which may be unknown.
std::optional<double> mostOf(std::optional<double> a, std::optional<double> b)
{
  return a && b ? std::max(*a, *b) : (a ? a : b);
}
}  // namespace

void MissionTracker::onMapStats(std::uint64_t overruns) { keepNewest(map_overruns_, overruns); }

void MissionTracker::onPathOverruns(std::uint64_t overruns) { keepNewest(path_overruns_, overruns); }

std::vector<std::string> MissionTracker::takeProgress() { return std::exchange(progress_, {}); }

void MissionTracker::finishAtGoal(double t, const std::string& outcome)
{
  if (collisions_ == 0) {
    finish(t, MissionEnd::kSuccess, outcome);
  } else {
    finish(t, MissionEnd::kFailed, fmt::format("{} after {} collisions", outcome, collisions_),
           fmt::format("{} collisions", collisions_));
  }
}

void MissionTracker::finish(double t, MissionEnd end, std::string outcome, std::string failure)
{
  finished_ = true;
  end_t_ = t;
  end_ = end;
  outcome_ = std::move(outcome);
  failure_ = std::move(failure);
}

MissionSummary MissionTracker::summary(double wall_s) const
{
  MissionSummary s;
  s.success = finished_ && end_ == MissionEnd::kSuccess;
  s.end = end_;
  s.outcome = finished_ ? outcome_ : "not finished";
  s.failure = s.success ? "" : (finished_ ? failure_ : "not finished");
  s.collisions = collisions_;
  // the run's sim time up to the mission's end, not up to the last state heard before it
  s.sim_s = finished_ ? end_t_ : t_;
  s.wall_s = wall_s;
  s.path_length_m = length_;
  s.straight_line_m = (goal_ - world_.start()).norm();
  if (mission_t_ && goal_t_ && *goal_t_ > *mission_t_) {
    s.time_to_goal_s = *goal_t_ - *mission_t_;
    s.average_speed_mps = (goal_length_ - mission_length_) / *s.time_to_goal_s;
  }
  s.top_speed_mps = top_speed_;
  const auto in_mission = [&](double t) {
    if (finished_ && t > end_t_) {
      return false;
    }
    const auto after = std::upper_bound(mode_times_.begin(), mode_times_.end(), t,
                                        [](double v, const auto& m) { return v < m.first; });
    return after != mode_times_.begin() && std::prev(after)->second == "MISSION";
  };
  std::vector<double> sorted;
  for (const auto& [t, latency] : depth_latencies_) {
    if (in_mission(t)) {
      sorted.push_back(latency);
    }
  }
  if (!sorted.empty()) {
    std::sort(sorted.begin(), sorted.end());
    s.depth_to_command_median_s = sorted[sorted.size() / 2];
    s.depth_to_command_max_s = sorted.back();
  }
  s.paths = static_cast<int>(std::count_if(path_times_.begin(), path_times_.end(),
                                           [&](double t) { return !finished_ || t <= end_t_; }));
  s.map_overruns = map_overruns_;
  s.path_overruns = path_overruns_;
  s.min_clearance_m = std::isfinite(min_clearance_) ? min_clearance_ : 0.0;
  s.mode_changes = static_cast<int>(modes_.size());
  s.modes = modes_;
  s.goal_distance_m = last_p_ ? (*last_p_ - goal_).norm() : s.straight_line_m;
  return s;
}

std::string_view toString(MissionEnd end)
{
  switch (end) {
    case MissionEnd::kUnfinished:
      return "unfinished";
    case MissionEnd::kSuccess:
      return "success";
    case MissionEnd::kFailed:
      return "failed";
    case MissionEnd::kNoPath:
      return "no_path";
    case MissionEnd::kCrashed:
      return "crashed";
  }
  return "?";
}

namespace {

/// Why a vehicle of `radius` cannot stand at p (`what` names the place): the nearest solid it
/// would touch, past what it stands on.
std::optional<std::string> tooNear(const world::World& world, const Eigen::Vector3d& p, double radius,
                                   const std::string& what)
{
  const auto near = world.nearest(p, radius, radius);
  if (!near || near->distance >= radius) {
    return std::nullopt;
  }
  return near->distance <= 0.0 ? fmt::format("{} lies inside {}", what, world.describe(near->id))
                               : fmt::format("{} lies {:.2f} m from {}, within the vehicle's radius ({} m)", what,
                                             near->distance, world.describe(near->id), radius);
}

}  // namespace

std::optional<std::string> goalProblem(const world::World& world, double radius, const common::Geofence& fence)
{
  const Eigen::Vector3d& g = world.goal();
  const std::string goal = fmt::format("the goal ({}, {}, {})", g.x(), g.y(), g.z());
  const auto fenced = [&](const std::string& what) {
    return fmt::format("{} is outside the geofence ({}, {}, {}) ... ({}, {}, {})", what, fence.min[0], fence.min[1],
                       fence.min[2], fence.max[0], fence.max[1], fence.max[2]);
  };
  if (!fence.contains(g)) {
    return fenced(goal);
  }
  if (const Eigen::Vector3d& s = world.start(); !fence.contains(s)) {
    return fenced(fmt::format("the start ({}, {}, {})", s.x(), s.y(), s.z()));
  }
  if (!world.bounds().contains(g)) {
    const auto& b = world.bounds();
    return fmt::format("{} is outside the world's bounds ({}, {}, {}) ... ({}, {}, {})", goal, b.min.x(), b.min.y(),
                       b.min.z(), b.max.x(), b.max.y(), b.max.z());
  }
  return tooNear(world, g, radius, goal);
}

world::World memberWorld(const world::World& world, const FleetMember& v)
{
  const Eigen::Vector3d start(v.start[0], v.start[1], v.start[2]);
  const Eigen::Vector3d goal = v.goal ? Eigen::Vector3d((*v.goal)[0], (*v.goal)[1], (*v.goal)[2]) : world.goal();
  return world.withStartAndGoal(start, goal);
}

std::vector<std::string> fleetProblems(const world::World& world, const std::vector<FleetMember>& vehicles,
                                       const std::vector<double>& radii, const common::Geofence& fence)
{
  std::vector<std::string> problems;
  const auto name = [&](std::size_t i) { return fmt::format("vehicles[{}] (id {})", i, vehicles[i].id); };
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const world::World own = memberWorld(world, vehicles[i]);
    const Eigen::Vector3d& s = own.start();
    const std::string start = fmt::format("the start ({}, {}, {})", s.x(), s.y(), s.z());
    if (const auto goal = goalProblem(own, radii[i], fence)) {
      problems.push_back(name(i) + ": " + *goal);
    } else if (!world.bounds().contains(s)) {
      problems.push_back(fmt::format("{}: {} is outside the world's bounds", name(i), start));
    } else if (const auto near = tooNear(world, s, radii[i], start)) {
      problems.push_back(name(i) + ": " + *near);
    }
    for (std::size_t j = 0; j < i; ++j) {
      const world::World other = memberWorld(world, vehicles[j]);
      const double gap = (s - other.start()).norm() - radii[i] - radii[j];
      if (gap < 0.0) {
        problems.push_back(fmt::format("{}: its start is {:.2f} m into {}'s: the two vehicles would start in contact",
                                       name(i), -gap, name(j)));
      }
    }
  }
  return problems;
}

MissionSummary fleetSummary(std::vector<MissionSummary> vehicles, std::optional<double> min_separation_m,
                            double wall_s)
{
  MissionSummary s;
  s.wall_s = wall_s;
  s.min_separation_m = min_separation_m;
  s.success = !vehicles.empty();
  s.end = MissionEnd::kSuccess;
  s.min_clearance_m = std::numeric_limits<double>::infinity();
  std::optional<double> optimum = 0.0;
  int succeeded = 0;
  for (const MissionSummary& v : vehicles) {
    const std::string who = fmt::format("vehicle {}", v.vehicle_id.value_or(0));
    if (v.success) {
      ++succeeded;
    } else {
      s.success = false;
      s.failure += fmt::format("{}{}: {}", s.failure.empty() ? "" : "; ", who, v.failure);
      // The first failure of another kind outranks a no-path end, which outranks success.
      if (s.end == MissionEnd::kSuccess || (s.end == MissionEnd::kNoPath && v.end != MissionEnd::kNoPath)) {
        s.end = v.end;
      }
    }
    s.collisions += v.collisions;
    s.sim_s = std::max(s.sim_s, v.sim_s);
    s.path_length_m += v.path_length_m;
    s.straight_line_m += v.straight_line_m;
    s.top_speed_mps = std::max(s.top_speed_mps, v.top_speed_mps);
    s.depth_to_command_median_s = mostOf(s.depth_to_command_median_s, v.depth_to_command_median_s);
    s.depth_to_command_max_s = mostOf(s.depth_to_command_max_s, v.depth_to_command_max_s);
    optimum = optimum && v.optimum_m ? std::optional<double>(*optimum + *v.optimum_m) : std::nullopt;
    s.paths += v.paths;
    addCount(s.map_overruns, v.map_overruns);
    addCount(s.path_overruns, v.path_overruns);
    s.min_clearance_m = std::min(s.min_clearance_m, v.min_clearance_m);
    s.mode_changes += v.mode_changes;
    s.goal_distance_m = std::max(s.goal_distance_m, v.goal_distance_m);
  }
  if (!std::isfinite(s.min_clearance_m)) {
    s.min_clearance_m = 0.0;
  }
  s.optimum_m = vehicles.empty() ? std::nullopt : optimum;
  s.outcome = fmt::format("{} of {} vehicles reached their goals", succeeded, vehicles.size());
  s.vehicles = std::move(vehicles);
  return s;
}

std::optional<double> busyShare(const ProcessCost& p, double wall_s)
{
  return p.cpu_s && wall_s > 0.0 ? std::optional<double>(*p.cpu_s / wall_s) : std::nullopt;
}

namespace {
nlohmann::ordered_json jsonOf(const MissionSummary& s)
{
  nlohmann::ordered_json j;
  if (s.vehicle_id) {
    j["vehicle_id"] = *s.vehicle_id;
  }
  j["success"] = s.success;
  j["outcome"] = s.outcome;
  j["end"] = toString(s.end);
  j["failure"] = s.failure;
  j["collisions"] = s.collisions;
  j["state"] = s.state;
  j["sim_seconds"] = s.sim_s;
  j["wall_seconds"] = s.wall_s;
  j["real_time_factor"] = s.wall_s > 0.0 ? nlohmann::ordered_json(s.sim_s / s.wall_s) : nlohmann::ordered_json(nullptr);
  const auto orNull = [](std::optional<double> v) { return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr); };
  j["startup_seconds"] = orNull(s.startup_s);
  j["flight_wall_seconds"] = orNull(s.flight_wall_s);
  j["path_length_m"] = s.path_length_m;
  j["straight_line_m"] = s.straight_line_m;
  j["time_to_goal_s"] = orNull(s.time_to_goal_s);
  j["average_speed_mps"] = orNull(s.average_speed_mps);
  j["top_speed_mps"] = s.top_speed_mps;
  j["depth_to_command_median_s"] = orNull(s.depth_to_command_median_s);
  j["depth_to_command_max_s"] = orNull(s.depth_to_command_max_s);
  j["optimum_m"] = s.optimum_m ? nlohmann::ordered_json(*s.optimum_m) : nlohmann::ordered_json(nullptr);
  j["flown_over_optimum"] = s.optimum_m && *s.optimum_m > 0.0 ? nlohmann::ordered_json(s.path_length_m / *s.optimum_m)
                                                              : nlohmann::ordered_json(nullptr);
  j["paths"] = s.paths;
  j["map_overruns"] = s.map_overruns ? nlohmann::ordered_json(*s.map_overruns) : nlohmann::ordered_json(nullptr);
  j["path_overruns"] = s.path_overruns ? nlohmann::ordered_json(*s.path_overruns) : nlohmann::ordered_json(nullptr);
  j["min_clearance_m"] = s.min_clearance_m;
  j["mode_changes"] = s.mode_changes;
  j["modes"] = s.modes;
  j["goal_distance_m"] = s.goal_distance_m;
  nlohmann::ordered_json processes = nlohmann::ordered_json::object();
  for (const ProcessCost& p : s.processes) {
    processes[p.name] = {{"cpu_seconds", orNull(p.cpu_s)},
                         {"busy_share", orNull(busyShare(p, s.wall_s))},
                         {"max_rss_mib", orNull(p.max_rss_mib)},
                         {"waits", p.waits ? nlohmann::ordered_json(*p.waits) : nlohmann::ordered_json(nullptr)}};
  }
  j["processes"] = processes;
  if (s.estimate) {
    const EstimateErrors& e = *s.estimate;
    j["estimate"] = {{"samples", e.samples},
                     {"position_rms_m", e.position_rms_m},
                     {"position_max_m", e.position_max_m},
                     {"attitude_rms_deg", e.attitude_rms_deg},
                     {"attitude_max_deg", e.attitude_max_deg},
                     {"yaw_rms_deg", e.yaw_rms_deg},
                     {"position_nees_mean", e.position_nees_mean},
                     {"within_3sigma", e.within_3sigma}};
    nlohmann::ordered_json bands = nlohmann::ordered_json::array();
    for (const EstimateBand& b : e.by_speed) {
      bands.push_back({{"from_mps", b.from_mps},
                       {"to_mps", std::isfinite(b.to_mps) ? nlohmann::ordered_json(b.to_mps) : nlohmann::ordered_json(nullptr)},
                       {"samples", b.samples},
                       {"position_rms_m", b.position_rms_m},
                       {"position_nees_mean", b.position_nees_mean}});
    }
    j["estimate"]["by_speed"] = bands;
  } else {
    j["estimate"] = nullptr;
  }
  if (!s.vehicles.empty()) {
    j["min_separation_m"] = s.min_separation_m ? nlohmann::ordered_json(*s.min_separation_m) : nlohmann::ordered_json(nullptr);
    nlohmann::ordered_json each = nlohmann::ordered_json::array();
    for (const MissionSummary& v : s.vehicles) {
      each.push_back(jsonOf(v));
    }
    j["vehicles"] = each;
  }
  return j;
}
}  // namespace

std::string toJson(const MissionSummary& s) { return jsonOf(s).dump(2) + "\n"; }

namespace {
/// "  CPU (share of a core): plant 12.1 s (0.32), ...": what each process cost; empty when
/// none is known.
std::string costText(const MissionSummary& s)
{
  std::string line;
  for (const ProcessCost& p : s.processes) {
    if (const auto share = busyShare(p, s.wall_s)) {
      line += fmt::format("{}{} {:.1f} s ({:.2f})", line.empty() ? "" : ", ", p.name, *p.cpu_s, *share);
    }
  }
  return line.empty() ? "" : "  CPU (share of a core): " + line + "\n";
}

/// "  estimate against the truth: ...": how far the estimator was off; empty without one.
std::string estimateText(const MissionSummary& s)
{
  if (!s.estimate) {
    return "";
  }
  const EstimateErrors& e = *s.estimate;
  std::string bands;
  for (const EstimateBand& b : e.by_speed) {
    bands += fmt::format("{}{}: {:.1f} cm, NEES {:.2f}", bands.empty() ? "" : "; ",
                         std::isfinite(b.to_mps) ? fmt::format("{:g}-{:g} m/s", b.from_mps, b.to_mps)
                                                 : fmt::format("{:g} m/s and over", b.from_mps),
                         100.0 * b.position_rms_m, b.position_nees_mean);
  }
  return fmt::format("  estimate against the truth: position {:.1f} cm RMS (max {:.1f}), attitude {:.2f} deg RMS (max "
                     "{:.2f}), yaw {:.2f} deg RMS; position NEES {:.2f} (3 if consistent), {:.1f} % within 3 sigma\n",
                     100.0 * e.position_rms_m, 100.0 * e.position_max_m, e.attitude_rms_deg, e.attitude_max_deg,
                     e.yaw_rms_deg, e.position_nees_mean, 100.0 * e.within_3sigma) +
         (bands.empty() ? "" : "  by the true speed: " + bands + "\n");
}
/// "  map updates over the mapper's budget: 3 (the lockstep clock waited for them)", and the
/// planner's paths alike; a line for each count heard.
std::string overrunText(const MissionSummary& s)
{
  const auto line = [](const std::optional<std::uint64_t>& count, const char* what) {
    return count ? fmt::format("  {}: {}{}\n", what, *count, *count > 0 ? " (the lockstep clock waited for them)" : "")
                 : std::string();
  };
  return line(s.map_overruns, "map updates over the mapper's budget") +
         line(s.path_overruns, "paths over the planner's budget");
}

/// How fast: the mission's time to the goal and average speed, and the top speed.
std::string speedText(const MissionSummary& s)
{
  const std::string top = fmt::format("top speed {:.1f} m/s", s.top_speed_mps);
  const std::string latency =
      s.depth_to_command_median_s && s.depth_to_command_max_s
          ? fmt::format("  from a depth frame to the command reacting to it: {:.2f} s (median), {:.2f} s at most\n",
                        *s.depth_to_command_median_s, *s.depth_to_command_max_s)
          : std::string();
  if (!s.time_to_goal_s || !s.average_speed_mps) {
    return "  " + top + "\n" + latency;
  }
  return fmt::format("  to the goal in {:.1f} s from the mission's start, at {:.1f} m/s on average; {}\n", *s.time_to_goal_s,
                     *s.average_speed_mps, top) + latency;
}

/// A fleet's vehicles, a line each, and the least separation; empty for one vehicle.
std::string fleetText(const MissionSummary& s)
{
  if (s.vehicles.empty()) {
    return "";
  }
  std::string text = s.min_separation_m
                         ? fmt::format("  least separation between two vehicles {:.2f} m\n", *s.min_separation_m)
                         : "";
  for (const MissionSummary& v : s.vehicles) {
    text += fmt::format("  vehicle {}: {} ({}); flown {:.1f} m{}; closest to an obstacle {:.2f} m; collisions {}\n",
                        v.vehicle_id.value_or(0), v.success ? "SUCCESS" : "FAILED", v.outcome, v.path_length_m,
                        v.optimum_m && *v.optimum_m > 0.0
                            ? fmt::format(" ({:.2f}x its {:.1f} m optimum)", v.path_length_m / *v.optimum_m, *v.optimum_m)
                            : "",
                        v.min_clearance_m, v.collisions);
  }
  return text;
}
}  // namespace

std::string toText(const MissionSummary& s)
{
  return fmt::format(
      "mission: {} ({})\n{}"
      "  flown on the {}; sim {:.1f} s in {:.1f} s wall ({:.1f}x)\n"
      "  flown {:.1f} m for a {:.1f} m straight line ({:.2f}x){}; {} paths from the planner\n"
      "  closest approach to an obstacle {:.2f} m; collisions {}; {} mode changes; ends {:.2f} m from the goal\n",
      s.success ? "SUCCESS" : "FAILED", s.outcome, s.failure.empty() ? "" : "  failure: " + s.failure + "\n", s.state, s.sim_s, s.wall_s, s.wall_s > 0 ? s.sim_s / s.wall_s : 0.0,
      s.path_length_m, s.straight_line_m, s.straight_line_m > 0 ? s.path_length_m / s.straight_line_m : 0.0,
      s.optimum_m && *s.optimum_m > 0.0
          ? fmt::format(", a {:.1f} m known-map optimum ({:.2f}x)", *s.optimum_m, s.path_length_m / *s.optimum_m)
          : "",
      s.paths, s.min_clearance_m, s.collisions, s.mode_changes, s.goal_distance_m) + speedText(s) + fleetText(s) +
         estimateText(s) + overrunText(s) + costText(s);
}

}  // namespace quad::launch
