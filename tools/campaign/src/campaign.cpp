// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/campaign.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "quad/common/params.hpp"
#include "quad/process/run.hpp"
#include "quad/process/spawn.hpp"
#include "quad/world/world_file.hpp"

namespace quad::campaign {

namespace fs = std::filesystem;

namespace {

std::optional<double> optionalNumber(const nlohmann::json& j, const char* key)
{
  return j.contains(key) && j[key].is_number() ? std::optional<double>(j[key].get<double>()) : std::nullopt;
}

std::string orDash(const std::optional<double>& v, const char* format)
{
  return v ? fmt::format(fmt::runtime(format), *v) : "-";
}

/// A run's `quad launch` command, without its folders.
std::vector<std::string> launchCommand(const CampaignOptions& options, const fs::path& world, std::uint64_t seed)
{
  std::vector<std::string> argv{options.quad.string(), "launch", options.manifest.string(), "--world", world.string(),
                                "--lockstep", "--seed", std::to_string(seed)};
  if (!options.state.empty()) {
    argv.insert(argv.end(), {"--state", options.state});
  }
  if (!options.layout.empty()) {
    argv.insert(argv.end(), {"--layout", options.layout});
  }
  return argv;
}

/// "forest.yaml with world:forest.density=0.04": a world variant in messages.
std::string describeVariant(const fs::path& world, const std::vector<std::pair<std::string, std::string>>& params)
{
  std::string text = world.string() + " with";
  for (const auto& [k, v] : params) {
    text += " " + k + "=" + v;
  }
  return text;
}

/// With several runs at once, slot k's network-namespace hosts live on <this>.k.0/24.
constexpr const char* kSlotSubnets = "10.78";

using Clock = std::chrono::steady_clock;
/// How long an interrupted run has to stop its modules before it is killed.
constexpr auto kInterruptGrace = std::chrono::seconds(20);

/// A run flying: its place in the product, its slot (and so its domain), its launcher.
struct Flying {
  std::size_t index = 0;
  std::size_t slot = 0;
  std::unique_ptr<process::Spawned> child;
  std::string output;
  std::optional<Clock::time_point> interrupted_at;
};

fs::path runFolder(const CampaignOptions& options, const PlannedRun& run)
{
  return options.dir / run.name;
}

/// In a run's folder once it ended: the launcher's exit status.
constexpr const char* kExitStatusFile = "exit_status";

/// A run's folder made ready (its world variant written, an old result removed) and its
/// `quad launch` command on `domain`, its netns hosts on `subnet` when given.
std::vector<std::string> prepareRun(const CampaignOptions& options, const PlannedRun& run, int domain,
                                    const std::optional<std::string>& subnet)
{
  const fs::path dir = runFolder(options, run);
  fs::create_directories(dir);
  fs::remove(dir / "summary.json");
  fs::remove(dir / kExitStatusFile);
  fs::path world = run.world;
  if (const auto params = run.worldParams(); !params.empty()) {
    world = dir / "world.yaml";
    std::ofstream(world) << "# " << describeVariant(run.world, params) << "\n" << worldVariant(run.world, params);
  }
  std::vector<std::string> argv = launchCommand(options, world, run.seed);
  argv.insert(argv.end(), {"--domain", std::to_string(domain), "--quiet", "--wall-timeout",
                           fmt::format("{}", options.wall_timeout_s), "--summary", (dir / "summary.json").string(),
                           "--log-dir", (dir / "run").string()});
  if (!options.record) {
    argv.emplace_back("--no-record");
  }
  if (subnet) {
    argv.insert(argv.end(), {"--subnet", *subnet});
  }
  for (const std::string& set : run.moduleSets()) {
    argv.insert(argv.end(), {"--set", set});
  }
  return argv;
}

Flying startRun(const CampaignOptions& options, const PlannedRun& run, std::size_t index, std::size_t slot)
{
  // two runs' network-namespace hosts on one /24 would share its addresses
  const auto subnet = options.jobs > 1 ? std::optional<std::string>(fmt::format("{}.{}", kSlotSubnets, slot)) : std::nullopt;
  const auto argv = prepareRun(options, run, options.domain + static_cast<int>(slot), subnet);
  return Flying{index, slot, std::make_unique<process::Spawned>(argv), {}, std::nullopt};
}

/// The run's result from its folder: its summary and the launcher's exit status.
CampaignRun resultOf(const CampaignOptions& options, const PlannedRun& run, int status)
{
  CampaignRun r = unflownRun(run);
  try {
    r = readRun(runFolder(options, run) / "summary.json", r.world, run.seed, status);
    r.name = run.name;
    r.params = run.params;
  } catch (const std::exception& e) {
    r.exit_status = status;
    r.failure = e.what();
  }
  return r;
}

CampaignRun finishRun(const CampaignOptions& options, const PlannedRun& run, int status, const std::string& output,
                      bool interrupted)
{
  const fs::path dir = runFolder(options, run);
  std::ofstream(dir / "launch.out") << output;
  if (!interrupted) {
    std::ofstream(dir / kExitStatusFile) << status << "\n";
  }
  CampaignRun r = resultOf(options, run, status);
  if (interrupted) {
    r.success = false;
    r.end = "interrupted";
    r.failure = "the campaign was stopped";
  }
  return r;
}

}  // namespace

std::string CampaignRun::param(const std::string& axis_key) const
{
  const auto it = std::find_if(params.begin(), params.end(), [&](const auto& kv) { return kv.first == axis_key; });
  return it == params.end() ? std::string() : it->second;
}

CampaignRun unflownRun(const PlannedRun& run)
{
  CampaignRun r;
  r.world = run.world.stem().string();
  r.seed = run.seed;
  r.name = run.name;
  r.params = run.params;
  return r;
}

CampaignRun readRun(const fs::path& summary, const std::string& world, std::uint64_t seed, int exit_status)
{
  std::ifstream in(summary);
  if (!in) {
    throw std::runtime_error(summary.string() + ": no summary (the run ended before its mission)");
  }
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object() || !j.contains("success") || !j.contains("collisions")) {
    throw std::runtime_error(summary.string() + ": not a mission summary");
  }
  CampaignRun r;
  r.world = world;
  r.seed = seed;
  r.exit_status = exit_status;
  r.success = j["success"].get<bool>() && exit_status == 0;
  r.end = j.value("end", "");
  r.failure = j.value("failure", "");
  r.collisions = j["collisions"].get<int>();
  r.path_length_m = j.value("path_length_m", 0.0);
  r.optimum_m = optionalNumber(j, "optimum_m");
  r.flown_over_optimum = optionalNumber(j, "flown_over_optimum");
  r.min_clearance_m = j.value("min_clearance_m", 0.0);
  r.time_to_goal_s = optionalNumber(j, "time_to_goal_s");
  r.average_speed_mps = optionalNumber(j, "average_speed_mps");
  r.top_speed_mps = j.value("top_speed_mps", 0.0);
  r.state = j.value("state", "");
  if (j.contains("estimate") && j["estimate"].is_object()) {
    r.estimate_rms_m = optionalNumber(j["estimate"], "position_rms_m");
    r.estimate_nees = optionalNumber(j["estimate"], "position_nees_mean");
  }
  r.depth_to_command_max_s = optionalNumber(j, "depth_to_command_max_s");
  r.replans = j.value("paths", 0);
  r.sim_s = j.value("sim_seconds", 0.0);
  r.wall_s = j.value("wall_seconds", 0.0);
  return r;
}

CampaignRun flyRun(const CampaignOptions& options, const PlannedRun& run, std::size_t index)
{
  // Tasks of a cluster fly at once in any number: each its own domain (from options.domain,
  // wrapping before 233) and netns subnet.
  const int domain = options.domain + static_cast<int>(index % static_cast<std::size_t>(233 - options.domain));
  const auto argv = prepareRun(options, run, domain, fmt::format("{}.{}", kSlotSubnets, index % 256));
  const process::RunResult result = process::run(argv);
  // a task cancelled mid-flight (its launcher stopped by the same signal) leaves no result
  return finishRun(options, run, result.status, result.output, options.stop && options.stop());
}

std::optional<CampaignRun> storedResult(const CampaignOptions& options, const PlannedRun& run)
{
  const fs::path dir = runFolder(options, run);
  std::ifstream status_file(dir / kExitStatusFile);
  int status = -1;
  if (!fs::exists(dir / "summary.json") || !(status_file >> status)) {
    return std::nullopt;
  }
  return resultOf(options, run, status);
}

std::vector<std::string> checkCampaign(const CampaignOptions& options)
{
  std::vector<std::string> problems;
  std::vector<PlannedRun> plan;
  try {
    plan = planRuns(options.worlds, options.axes, options.seeds);
  } catch (const common::ConfigError& e) {
    return e.problems();
  }
  std::set<std::vector<std::string>> module_sets;
  std::set<std::pair<fs::path, std::vector<std::pair<std::string, std::string>>>> worlds;
  for (const PlannedRun& r : plan) {
    if (module_sets.insert(r.moduleSets()).second) {
      std::vector<std::string> argv = launchCommand(options, r.world, r.seed);
      argv.emplace_back("--check");
      for (const std::string& set : r.moduleSets()) {
        argv.insert(argv.end(), {"--set", set});
      }
      const process::RunResult result = process::run(argv);
      if (result.status != 0) {
        std::istringstream lines(result.output);
        for (std::string line; std::getline(lines, line);) {
          if (!line.empty()) {
            problems.push_back(line);
          }
        }
      }
    }
    if (const auto params = r.worldParams(); !params.empty() && worlds.emplace(r.world, params).second) {
      try {
        (void)world::parseWorld(worldVariant(r.world, params), describeVariant(r.world, params));
      } catch (const common::ConfigError& e) {
        problems.insert(problems.end(), e.problems().begin(), e.problems().end());
      }
    }
  }
  return problems;
}

std::vector<CampaignRun> runCampaign(const CampaignOptions& options,
                                     const std::function<void(const CampaignRun&)>& progress)
{
  const std::vector<PlannedRun> plan = planRuns(options.worlds, options.axes, options.seeds);
  const std::size_t jobs = static_cast<std::size_t>(std::max(1, options.jobs));
  std::vector<std::optional<CampaignRun>> results(plan.size());
  std::vector<Flying> flying;
  std::vector<bool> slot_busy(jobs, false);
  std::size_t next = 0;
  bool stopping = false;
  while ((!stopping && next < plan.size()) || !flying.empty()) {
    if (!stopping && options.stop && options.stop()) {
      stopping = true;
      for (Flying& f : flying) {
        f.child->signal(SIGINT);
        f.interrupted_at = Clock::now();
      }
    }
    while (!stopping && next < plan.size() && flying.size() < jobs) {
      const std::size_t slot = static_cast<std::size_t>(std::find(slot_busy.begin(), slot_busy.end(), false) -
                                                        slot_busy.begin());
      flying.push_back(startRun(options, plan[next], next, slot));
      slot_busy[slot] = true;
      ++next;
    }
    std::vector<pollfd> fds;
    for (const Flying& f : flying) {
      fds.push_back({f.child->outputFd(), POLLIN, 0});
    }
    ::poll(fds.data(), fds.size(), 100);
    for (auto f = flying.begin(); f != flying.end();) {
      f->child->readOutput(f->output);
      if (f->interrupted_at && Clock::now() - *f->interrupted_at > kInterruptGrace) {
        f->child->signal(SIGKILL);
      }
      const std::optional<int> status = f->child->poll();
      if (!status) {
        ++f;
        continue;
      }
      f->child->readOutput(f->output);
      CampaignRun r = finishRun(options, plan[f->index], *status, f->output, f->interrupted_at.has_value());
      if (progress) {
        progress(r);
      }
      results[f->index] = std::move(r);
      slot_busy[f->slot] = false;
      f = flying.erase(f);
    }
  }
  std::vector<CampaignRun> runs;
  for (auto& r : results) {
    if (r) {
      runs.push_back(std::move(*r));
    }
  }
  return runs;
}

std::string table(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes)
{
  std::string axis_header;
  for (const std::string& label : axisLabels(axes)) {
    axis_header += fmt::format(" {:>10}", label);
  }
  std::string out = fmt::format("{:<14}{} {:>4}  {:<8} {:<8} {:>10} {:>12} {:>10} {:>9} {:>7} {:>7} {:>7} {:>8} {:>8}  {}\n",
                                "world", axis_header, "seed", "result", "state", "collisions", "flown/opt", "closest_m",
                                "est_rms_m", "avg_m/s", "top_m/s", "replans", "sim_s", "wall_s", "failure");
  int ok = 0;
  for (const CampaignRun& r : runs) {
    ok += r.success ? 1 : 0;
    std::string axis_cells;
    for (const Axis& a : axes) {
      const std::string value = r.param(a.key);
      axis_cells += fmt::format(" {:>10}", value.empty() ? "-" : value);
    }
    out += fmt::format("{:<14}{} {:>4}  {:<8} {:<8} {:>10} {:>12} {:>10.2f} {:>9} {:>7} {:>7.1f} {:>7} {:>8.1f} {:>8.1f}  {}\n",
                       r.world, axis_cells, r.seed, r.success ? "ok" : (r.end.empty() ? "error" : r.end),
                       r.state.empty() ? "-" : r.state, r.collisions, orDash(r.flown_over_optimum, "{:.3f}"),
                       r.min_clearance_m, orDash(r.estimate_rms_m, "{:.3f}"), orDash(r.average_speed_mps, "{:.1f}"),
                       r.top_speed_mps, r.replans, r.sim_s, r.wall_s, r.failure);
  }
  out += fmt::format("{} of {} runs succeeded\n", ok, runs.size());
  return out;
}

std::string toJson(const std::vector<CampaignRun>& runs, const std::vector<Axis>& axes)
{
  const auto number = [](const std::optional<double>& v) {
    return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
  };
  nlohmann::ordered_json j;
  j["axes"] = nlohmann::ordered_json::object();
  for (const Axis& a : axes) {
    j["axes"][a.key] = a.values;
  }
  j["runs"] = nlohmann::ordered_json::array();
  int ok = 0;
  for (const CampaignRun& r : runs) {
    ok += r.success ? 1 : 0;
    nlohmann::ordered_json row;
    row["world"] = r.world;
    row["name"] = r.name;
    row["params"] = nlohmann::ordered_json::object();
    for (const auto& [k, v] : r.params) {
      row["params"][k] = v;
    }
    row["seed"] = r.seed;
    row["exit_status"] = r.exit_status;
    row["success"] = r.success;
    row["end"] = r.end;
    row["failure"] = r.failure;
    row["collisions"] = r.collisions;
    row["path_length_m"] = r.path_length_m;
    row["optimum_m"] = number(r.optimum_m);
    row["flown_over_optimum"] = number(r.flown_over_optimum);
    row["min_clearance_m"] = r.min_clearance_m;
    row["time_to_goal_s"] = number(r.time_to_goal_s);
    row["average_speed_mps"] = number(r.average_speed_mps);
    row["top_speed_mps"] = r.top_speed_mps;
    row["state"] = r.state;
    row["estimate_rms_m"] = number(r.estimate_rms_m);
    row["estimate_nees"] = number(r.estimate_nees);
    row["depth_to_command_max_s"] = number(r.depth_to_command_max_s);
    row["replans"] = r.replans;
    row["sim_seconds"] = r.sim_s;
    row["wall_seconds"] = r.wall_s;
    j["runs"].push_back(row);
  }
  j["succeeded"] = ok;
  j["runs_total"] = runs.size();
  return j.dump(2) + "\n";
}

}  // namespace quad::campaign
