// SPDX-License-Identifier: BSD-3-Clause
#include "campaign_command.hpp"

#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "quad/launch/run.hpp"
#include "quad/campaign/campaign.hpp"
#include "quad/dds/participant.hpp"

namespace quad::tools {

namespace fs = std::filesystem;

int campaign(const CampaignCommandOptions& options)
{
  campaign::CampaignOptions c;
  c.quad = fs::read_symlink("/proc/self/exe");
  c.manifest = fs::absolute(launch::findManifest(options.manifest, common::layout()));
  c.seeds = options.seeds;
  for (const auto& w : options.worlds) {
    if (!fs::is_regular_file(w)) {
      std::fprintf(stderr, "campaign: %s: no such world file\n", w.c_str());
      return launch::kExitInvalid;
    }
    c.worlds.push_back(fs::absolute(w));
  }
  try {
    c.domain = options.domain ? *options.domain : dds::optionsFromEnvironment("quad_campaign").domain_id;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campaign: %s\n", e.what());
    return launch::kExitInvalid;
  }
  c.dir = fs::absolute(options.dir ? fs::path(*options.dir) : fs::path("log") / launch::runFolderName("campaign"));
  c.wall_timeout_s = options.wall_timeout_s;
  c.state = options.state;
  c.layout = options.layout;
  fs::create_directories(c.dir);
  std::printf("campaign: %zu worlds x %d seeds, runs in %s\n", c.worlds.size(), c.seeds, c.dir.string().c_str());
  std::fflush(stdout);
  const auto runs = campaign::runCampaign(c, [](const campaign::CampaignRun& r) {
    std::printf("campaign: %s seed %llu: %s in %.0f s wall%s\n", r.world.c_str(), static_cast<unsigned long long>(r.seed),
                r.success ? "ok" : "FAILED", r.wall_s, r.failure.empty() ? "" : (" (" + r.failure + ")").c_str());
    std::fflush(stdout);
  });
  std::printf("%s", campaign::table(runs).c_str());
  const fs::path json = options.json ? fs::path(*options.json) : c.dir / "campaign.json";
  std::ofstream out(json);
  out << campaign::toJson(runs);
  if (!out) {
    std::fprintf(stderr, "campaign: cannot write %s\n", json.string().c_str());
    return launch::kExitFailed;
  }
  std::printf("campaign: %s\n", json.string().c_str());
  const bool all = std::all_of(runs.begin(), runs.end(), [](const campaign::CampaignRun& r) { return r.success; });
  return all ? 0 : launch::kExitFailed;
}

}  // namespace quad::tools
