// SPDX-License-Identifier: BSD-3-Clause
#include "plan_command.hpp"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "quad/launch/run.hpp"
#include "quad/plan/known_map.hpp"

namespace quad::tools {

int plan(const PlanOptions& options)
{
  try {
    std::optional<plan::PlanningSetup> from_manifest;
    if (options.manifest) {
      launch::LaunchOptions run;
      run.manifest = *options.manifest;
      run.world = options.world;
      const auto m = launch::loadRunManifest(run);  // its problems are on stderr
      if (!m) {
        return launch::kExitInvalid;
      }
      from_manifest = launch::manifestPlanningSetup(*m);
      if (!from_manifest) {
        std::fprintf(stderr, "plan: %s has no planning module\n", options.manifest->c_str());
        return launch::kExitInvalid;
      }
    }
    std::vector<common::ParamOverride> overrides;
    if (options.world) {
      overrides.push_back({"world", std::filesystem::absolute(*options.world).string()});
    }
    const plan::PlanningSetup setup = from_manifest ? *std::move(from_manifest) : plan::loadPlanningSetup(options.config, overrides);
    const plan::KnownMapPlan p = plan::planOnKnownMap(setup.world, setup.params, !options.no_land);
    const auto& g = setup.world.goal();
    std::printf("%s: %s\n", setup.world_file.string().c_str(), std::string(toString(p.status)).c_str());
    if (p.status == planning::PlanStatus::kOk) {
      std::printf("optimum %.2f m: climb %.2f m to (%.1f, %.1f, %.1f), path %.2f m (%zu waypoints) to the goal "
                  "(%.1f, %.1f, %.1f), landing %.2f m\n",
                  p.optimum_m, p.climb_m, p.from.x(), p.from.y(), p.from.z(), p.path_m, p.waypoints.size(), g.x(),
                  g.y(), g.z(), p.landing_m);
    }
    std::printf("%zu obstacle voxels at %.2f m, inflation %.2f m, %llu expansions\n", p.occupied_voxels,
                setup.params.resolution, setup.params.planner.vehicle_radius, static_cast<unsigned long long>(p.expansions));
    if (options.json) {
      nlohmann::ordered_json j;
      j["world"] = setup.world_file.string();
      j["status"] = std::string(toString(p.status));
      j["optimum_m"] = p.status == planning::PlanStatus::kOk ? nlohmann::ordered_json(p.optimum_m) : nullptr;
      j["path_m"] = p.path_m;
      j["climb_m"] = p.climb_m;
      j["landing_m"] = p.landing_m;
      j["waypoints"] = nlohmann::ordered_json::array();
      for (const auto& w : p.waypoints) {
        j["waypoints"].push_back({w.x(), w.y(), w.z()});
      }
      std::ofstream out(*options.json);
      out << j.dump(2) << "\n";
      if (!out) {
        std::fprintf(stderr, "plan: cannot write %s\n", options.json->c_str());
        return launch::kExitFailed;
      }
    }
    return p.status == planning::PlanStatus::kOk ? 0 : launch::kExitNoPath;
  } catch (const common::ConfigError& e) {
    for (const auto& problem : e.problems()) {
      std::fprintf(stderr, "%s\n", problem.c_str());
    }
    return launch::kExitInvalid;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plan: %s\n", e.what());
    return launch::kExitInvalid;
  }
}

}  // namespace quad::tools
