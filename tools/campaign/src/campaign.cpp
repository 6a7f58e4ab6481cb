// SPDX-License-Identifier: BSD-3-Clause
#include "quad/campaign/campaign.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>

#include "quad/process/run.hpp"

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

}  // namespace

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

std::vector<CampaignRun> runCampaign(const CampaignOptions& options,
                                     const std::function<void(const CampaignRun&)>& progress)
{
  std::vector<CampaignRun> runs;
  for (const fs::path& world : options.worlds) {
    for (int seed = 1; seed <= options.seeds; ++seed) {
      const fs::path dir = options.dir / fmt::format("{}-seed{}", world.stem().string(), seed);
      fs::create_directories(dir);
      const fs::path summary = dir / "summary.json";
      fs::remove(summary);
      std::vector<std::string> argv{options.quad.string(), "launch", options.manifest.string(), "--world",
                                    world.string(), "--lockstep", "--seed", std::to_string(seed), "--domain",
                                    std::to_string(options.domain), "--quiet", "--wall-timeout",
                                    fmt::format("{}", options.wall_timeout_s), "--summary", summary.string(),
                                    "--log-dir", (dir / "run").string()};
      if (!options.state.empty()) {
        argv.insert(argv.end(), {"--state", options.state});
      }
      if (!options.layout.empty()) {
        argv.insert(argv.end(), {"--layout", options.layout});
      }
      const process::RunResult result = process::run(argv);
      std::ofstream(dir / "launch.out") << result.output;
      CampaignRun r;
      try {
        r = readRun(summary, world.stem().string(), static_cast<std::uint64_t>(seed), result.status);
      } catch (const std::exception& e) {
        r.world = world.stem().string();
        r.seed = static_cast<std::uint64_t>(seed);
        r.exit_status = result.status;
        r.failure = e.what();
      }
      runs.push_back(r);
      if (progress) {
        progress(r);
      }
    }
  }
  return runs;
}

std::string table(const std::vector<CampaignRun>& runs)
{
  std::string out = fmt::format("{:<14} {:>4}  {:<8} {:<8} {:>10} {:>12} {:>10} {:>9} {:>7} {:>7} {:>7} {:>8} {:>8}  {}\n",
                                "world", "seed", "result", "state", "collisions", "flown/opt", "closest_m", "est_rms_m",
                                "avg_m/s", "top_m/s", "replans", "sim_s", "wall_s", "failure");
  int ok = 0;
  for (const CampaignRun& r : runs) {
    ok += r.success ? 1 : 0;
    out += fmt::format("{:<14} {:>4}  {:<8} {:<8} {:>10} {:>12} {:>10.2f} {:>9} {:>7} {:>7.1f} {:>7} {:>8.1f} {:>8.1f}  {}\n",
                       r.world, r.seed, r.success ? "ok" : (r.end.empty() ? "error" : r.end),
                       r.state.empty() ? "-" : r.state, r.collisions, orDash(r.flown_over_optimum, "{:.3f}"),
                       r.min_clearance_m, orDash(r.estimate_rms_m, "{:.3f}"), orDash(r.average_speed_mps, "{:.1f}"),
                       r.top_speed_mps, r.replans, r.sim_s, r.wall_s, r.failure);
  }
  out += fmt::format("{} of {} runs succeeded\n", ok, runs.size());
  return out;
}

std::string toJson(const std::vector<CampaignRun>& runs)
{
  nlohmann::ordered_json j;
  j["runs"] = nlohmann::ordered_json::array();
  int ok = 0;
  for (const CampaignRun& r : runs) {
    ok += r.success ? 1 : 0;
    nlohmann::ordered_json row;
    row["world"] = r.world;
    row["seed"] = r.seed;
    row["exit_status"] = r.exit_status;
    row["success"] = r.success;
    row["end"] = r.end;
    row["failure"] = r.failure;
    row["collisions"] = r.collisions;
    row["path_length_m"] = r.path_length_m;
    row["optimum_m"] = r.optimum_m ? nlohmann::ordered_json(*r.optimum_m) : nlohmann::ordered_json(nullptr);
    row["flown_over_optimum"] =
        r.flown_over_optimum ? nlohmann::ordered_json(*r.flown_over_optimum) : nlohmann::ordered_json(nullptr);
    row["min_clearance_m"] = r.min_clearance_m;
    row["time_to_goal_s"] = r.time_to_goal_s ? nlohmann::ordered_json(*r.time_to_goal_s) : nlohmann::ordered_json(nullptr);
    row["average_speed_mps"] =
        r.average_speed_mps ? nlohmann::ordered_json(*r.average_speed_mps) : nlohmann::ordered_json(nullptr);
    row["top_speed_mps"] = r.top_speed_mps;
    row["state"] = r.state;
    row["estimate_rms_m"] = r.estimate_rms_m ? nlohmann::ordered_json(*r.estimate_rms_m) : nlohmann::ordered_json(nullptr);
    row["estimate_nees"] = r.estimate_nees ? nlohmann::ordered_json(*r.estimate_nees) : nlohmann::ordered_json(nullptr);
    row["depth_to_command_max_s"] =
        r.depth_to_command_max_s ? nlohmann::ordered_json(*r.depth_to_command_max_s) : nlohmann::ordered_json(nullptr);
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
